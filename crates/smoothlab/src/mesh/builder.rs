//! Building a mesh: nodes and elements as a file gives them, checked, mapped to the
//! mesh's plane, oriented, with the topology built and the fixed flags set.

use std::sync::Arc;

use glam::DVec2;

use crate::error::{Error, Numbering, Result};

use super::*;

/// Signed area of a polygon given by its vertices in order (shoelace formula).
pub fn polygon_area(pts: impl Iterator<Item = DVec2> + Clone) -> f64 {
    let first = pts.clone().next();
    let Some(first) = first else { return 0.0 };
    let mut s = 0.0;
    let mut prev = first;
    for p in pts.skip(1) {
        s += prev.perp_dot(p);
        prev = p;
    }
    s += prev.perp_dot(first);
    0.5 * s
}

/// How the fixed flags of a mesh are decided.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum FixedSpec {
    /// Boundary nodes (of corner-to-corner edges used by one element, with their mid nodes).
    #[default]
    Boundary,
    /// Exactly as the file says (VTK `POINT_DATA` scalar `fixed`).
    Exact(Vec<bool>),
    /// Boundary nodes plus the nodes the file marks (Gmsh line/point elements,
    /// Triangle boundary markers).
    BoundaryAnd(Vec<bool>),
}

/// The largest coordinate magnitude smoothlab computes with, `f64::MAX / 16` (about
/// 1.1e307): differences of coordinates and the end tangents `4M − 3P0 − P2` of quadratic
/// edges stay finite below it.
pub const MAX_COORDINATE: f64 = f64::MAX / 16.0;

/// Why a coordinate cannot be computed with, if it cannot: beyond [`MAX_COORDINATE`].
/// (Tiny ones are fine: a subnormal next to 1e-300 is a jittered zero, and the metrics
/// work in each element's own scale.)
fn beyond_arithmetic(c: f64) -> Option<String> {
    (c.abs() > MAX_COORDINATE).then(|| {
        format!(
            "coordinate {c:e} is too large to compute with: smoothlab takes magnitudes up to {MAX_COORDINATE:.1e} \
             (differences and quadratic edge tangents of larger ones overflow 64-bit floats)"
        )
    })
}

/// Relative tolerance within which 3D points count as planar: of the size of a node's
/// elements, or of its coordinates' magnitude (rounding), whichever is larger.
pub const PLANAR_TOLERANCE: f64 = 1e-5;

/// Collects what a reader found in a file, then validates it and builds a [`Mesh`].
/// Readers record the file line of every node and element so that errors found here
/// can still name the line.
#[derive(Clone, Debug, Default)]
pub struct MeshBuilder {
    points: Vec<[f64; 3]>,
    point_lines: Vec<u32>,
    kinds: Vec<ElementKind>,
    elem_start: Vec<u32>,
    elem_nodes: Vec<u32>,
    elem_lines: Vec<u32>,
    /// Volume elements (built into a volume mesh above this module): node ids in VTK's
    /// order, with their lines and kinds; a file with any is a volume mesh.
    tets: Vec<u32>,
    tet_lines: Vec<u32>,
    volume_kinds: Vec<super::VolumeKind>,
    /// How the file numbers its nodes, its triangles and quads, and its volume elements,
    /// so that every message names them as the file does.
    node_numbers: Numbering,
    element_numbers: Numbering,
    volume_numbers: Numbering,
    /// How fixed flags are decided.
    pub fixed: FixedSpec,
}

/// What a message about a file's mesh names its nodes and elements by: the file's lines
/// and numbers (`Numbering`). Built meshes have none: then 0-based indices, no line.
#[derive(Clone, Copy)]
pub(crate) struct FileNames<'a> {
    pub lines: &'a [u32],
    pub nodes: &'a Numbering,
    pub elements: &'a Numbering,
}

impl FileNames<'_> {
    /// No lines, 0-based numbers.
    pub const NONE: FileNames<'static> = FileNames { lines: &[], nodes: &Numbering::From(0), elements: &Numbering::From(0) };
    /// The file line of element `e`, when known.
    pub fn line(&self, e: usize) -> Option<usize> {
        self.lines.get(e).copied().filter(|&l| l > 0).map(|l| l as usize)
    }
    /// The file's number of node `i`.
    pub fn node(&self, i: usize) -> u64 {
        self.nodes.of(i)
    }
    /// The file's number of element `e`.
    pub fn element(&self, e: usize) -> u64 {
        self.elements.of(e)
    }
}

/// A planar mesh, or the parts of a surface in 3D
/// ([`MeshBuilder::build_planar_or_surface`]).
#[allow(clippy::large_enum_variant)]
pub(crate) enum Flat {
    Planar(Mesh),
    Surface(SurfaceParts),
}

/// What a surface in 3D is built from (by the surface module): its points as given, and a
/// planar [`Mesh`] with its elements, topology and fixed flags whose 2D positions are
/// scratch (zero).
pub(crate) struct SurfaceParts {
    pub points: Vec<glam::DVec3>,
    pub mesh: Mesh,
    /// How the file numbers the elements (for messages).
    pub element_numbers: Numbering,
    /// Whether the file gave the fixed flags.
    pub flags_given: bool,
    /// Why the points were not read as a planar mesh (see `Surface::not_planar`).
    pub not_planar: Option<String>,
}

/// What a volume mesh is built from (by the volume module): the nodes, the volume
/// elements, the file's triangles and quads (CSR, with their lines: the boundary faces
/// Gmsh writes) and the fixed flags' rule with those faces' nodes marked.
pub(crate) struct VolumeParts {
    pub points: Vec<[f64; 3]>,
    pub point_lines: Vec<u32>,
    pub face_kinds: Vec<ElementKind>,
    pub face_start: Vec<u32>,
    pub face_nodes: Vec<u32>,
    pub face_lines: Vec<u32>,
    /// Node ids, `kinds[e].nodes()` for element `e`, in VTK's order.
    pub tets: Vec<u32>,
    pub tet_lines: Vec<u32>,
    /// The kind of every volume element.
    pub kinds: Vec<super::VolumeKind>,
    /// How the file numbers its nodes and its volume elements (for messages).
    pub node_numbers: Numbering,
    pub volume_numbers: Numbering,
    pub fixed: FixedSpec,
}

impl MeshBuilder {
    pub fn new() -> Self {
        MeshBuilder { elem_start: vec![0], ..Default::default() }
    }
    /// A builder with room reserved for the given counts, capped (at 2¹⁶ of each) so a
    /// header that claims large counts costs a fixed amount until the data is seen;
    /// beyond that the arrays grow as nodes and elements are added.
    pub fn with_capacity(nodes: usize, elements: usize) -> Self {
        const CAP: usize = 1 << 16;
        let mut b = Self::new();
        b.points.reserve(nodes.min(CAP));
        b.point_lines.reserve(nodes.min(CAP));
        b.kinds.reserve(elements.min(CAP));
        b.elem_lines.reserve(elements.min(CAP));
        b
    }
    /// Reserves room for exactly this many more nodes, elements and element node ids (for
    /// counts that are known, not claimed by a file): no array then grows by doubling,
    /// which in wasm copies it and holds both copies for a moment.
    pub(crate) fn reserve_exact(&mut self, nodes: usize, elements: usize, element_nodes: usize) {
        self.points.reserve_exact(nodes);
        self.point_lines.reserve_exact(nodes);
        self.kinds.reserve_exact(elements);
        self.elem_start.reserve_exact(elements);
        self.elem_lines.reserve_exact(elements);
        self.elem_nodes.reserve_exact(element_nodes);
    }
    /// How the file numbers its nodes (0-based in file order unless a reader says): every
    /// message then names a node by its number in the file.
    pub fn number_nodes(&mut self, numbering: Numbering) {
        self.node_numbers = numbering;
    }
    /// The file's number of node `i` (0-based in file order).
    pub(crate) fn node_number(&self, i: usize) -> u64 {
        self.node_numbers.of(i)
    }
    /// Adds a node given in 3D (`z = 0` for 2D formats); `line` is its file line (0 if none).
    pub fn add_node(&mut self, p: [f64; 3], line: usize) -> usize {
        self.points.push(p);
        self.point_lines.push(line as u32);
        self.points.len() - 1
    }
    pub fn node_count(&self) -> usize {
        self.points.len()
    }
    pub fn element_count(&self) -> usize {
        self.kinds.len()
    }
    /// The file line of every node added (0 where none was given).
    pub(crate) fn node_lines(&self) -> &[u32] {
        &self.point_lines
    }
    /// Adds a volume element of `kind` with 0-based node indices in VTK's order (its row's
    /// order: a 10-node tetrahedron's mid-edge nodes on the edges of `TET10_EDGES`, a
    /// wedge's first triangle turning away from its second), checked when the volume mesh is
    /// built (`Model::build`). Linear kinds mix freely; a file that mixes a quadratic kind
    /// with another ([`VolumeKind::mixes_with`]) is refused here, naming the element (its
    /// number among the file's volume elements) and the line.
    ///
    /// [`VolumeKind::mixes_with`]: super::VolumeKind::mixes_with
    pub fn add_volume_element(&mut self, kind: super::VolumeKind, nodes: &[u32], line: usize) -> Result<()> {
        let number = self.volume_numbers.next(self.volume_kinds.len());
        self.add_volume_element_numbered(kind, nodes, line, number)
    }
    /// [`add_volume_element`](Self::add_volume_element) for an element the file numbers
    /// `number` (a Gmsh tag, a VTK cell index, a Medit number in its section).
    pub fn add_volume_element_numbered(
        &mut self,
        kind: super::VolumeKind,
        nodes: &[u32],
        line: usize,
        number: u64,
    ) -> Result<()> {
        debug_assert_eq!(nodes.len(), kind.nodes());
        // against the first kind: all linear, or all the first's quadratic kind
        if let Some(&k) = self.volume_kinds.first().filter(|&&k| !super::VolumeKind::mixes_with(k, kind)) {
            return Err(Error::element(
                number,
                Some(line).filter(|&l| l > 0),
                format!(
                    "the file mixes {}: smoothlab mixes linear kinds, but a quadratic mesh is of one kind",
                    super::VolumeKind::mix_words(k, kind)
                ),
            ));
        }
        self.volume_numbers.push(self.volume_kinds.len(), number);
        self.volume_kinds.push(kind);
        self.tets.extend_from_slice(nodes);
        self.tet_lines.push(line as u32);
        Ok(())
    }

    /// Whether volume elements were added (of any kind): then the file is a volume mesh
    /// (`build_volume_parts`).
    pub fn has_tets(&self) -> bool {
        !self.tets.is_empty()
    }

    /// The parts of the volume mesh of the volume elements added, for the volume module
    /// to build (which marks the nodes of the file's triangles and quads fixed, as lines
    /// and points are). Refuses a face naming a node the file does not have.
    pub(crate) fn build_volume_parts(self) -> Result<VolumeParts> {
        let n = self.points.len();
        for e in 0..self.kinds.len() {
            let ids = &self.elem_nodes[self.elem_start[e] as usize..self.elem_start[e + 1] as usize];
            if let Some(&i) = ids.iter().find(|&&i| i as usize >= n) {
                return Err(Error::element(
                    self.element_numbers.of(e),
                    self.line_of_elem(e),
                    format!("node {} does not exist (the file has {n} nodes)", self.node_number(i as usize)),
                ));
            }
        }
        let fixed = self.fixed;
        Ok(VolumeParts {
            points: self.points,
            point_lines: self.point_lines,
            face_kinds: self.kinds,
            face_start: self.elem_start,
            face_nodes: self.elem_nodes,
            face_lines: self.elem_lines,
            kinds: self.volume_kinds,
            tets: self.tets,
            tet_lines: self.tet_lines,
            node_numbers: self.node_numbers,
            volume_numbers: self.volume_numbers,
            fixed,
        })
    }

    /// Adds an element with 0-based node indices (checked in [`build`](Self::build)).
    pub fn add_element(&mut self, kind: ElementKind, nodes: &[u32], line: usize) {
        let number = self.element_numbers.next(self.kinds.len());
        self.add_element_numbered(kind, nodes, line, number)
    }
    /// [`add_element`](Self::add_element) for an element the file numbers `number` (a
    /// Gmsh tag, a VTK cell index, a Medit number in its section).
    pub fn add_element_numbered(&mut self, kind: ElementKind, nodes: &[u32], line: usize, number: u64) {
        debug_assert_eq!(nodes.len(), kind.node_count());
        self.element_numbers.push(self.kinds.len(), number);
        self.kinds.push(kind);
        self.elem_nodes.extend_from_slice(nodes);
        self.elem_start.push(self.elem_nodes.len() as u32);
        self.elem_lines.push(line as u32);
    }
    fn line_of_elem(&self, e: usize) -> Option<usize> {
        self.elem_lines.get(e).copied().filter(|&l| l > 0).map(|l| l as usize)
    }
    fn line_of_node(&self, n: usize) -> Option<usize> {
        self.point_lines.get(n).copied().filter(|&l| l > 0).map(|l| l as usize)
    }

    /// Validates (finite coordinates, indices in range, no repeated node in an element,
    /// at least one element, planarity), maps 3D points to the mesh's plane, orients
    /// the mesh counter-clockwise as a whole, builds the topology and the fixed flags.
    pub fn build(self) -> Result<Mesh> {
        if self.has_tets() {
            return Err(Error::unsupported(
                self.tet_lines.first().map(|&l| l as usize).filter(|&l| l > 0),
                "the file holds volume elements, not a planar mesh (smoothlab's stats and smooth take volume meshes)",
            ));
        }
        self.check()?;
        let flat = self.to_plane()?;
        self.planar(flat)
    }

    /// The planar mesh of the checked nodes and elements, with their 2D coordinates and
    /// plane from [`to_plane`](Self::to_plane).
    fn planar(mut self, (nodes, plane): (Vec<DVec2>, Option<Plane>)) -> Result<Mesh> {
        let n = self.points.len();
        // the 3D points are not needed past the plane, unless it is tilted (then they are
        // written back as given while their nodes stay): let them go before the topology
        // is built (24 bytes a node), and give back what the readers' growing left unused
        let tilted = plane.is_some_and(|p| p.u != glam::DVec3::X || p.w != glam::DVec3::Y);
        let points = std::mem::take(&mut self.points);
        let loaded_3d = tilted.then(|| points.iter().map(|&p| glam::DVec3::from(p)).collect::<Vec<_>>());
        drop(points);
        let (mut kinds, mut elem_start, mut elem_nodes) = (self.kinds, self.elem_start, self.elem_nodes);
        kinds.shrink_to_fit();
        elem_start.shrink_to_fit();
        elem_nodes.shrink_to_fit();
        let mut mesh = Mesh {
            plane,
            nodes,
            fixed: vec![false; n],
            conn: Arc::new(Connectivity { kinds, elem_start, elem_nodes, topo: Topology::default(), reversed: Vec::new() }),
            loaded_3d: None,
            target: None,
            given_fixed: None,
            sliding: None,
        };
        if let Some(points) = loaded_3d {
            mesh.keep_loaded_3d(points);
        }
        // Orientation of the whole mesh by its total signed area, decided by the sign of
        // total − (total of the reversed mesh), each summed as its own corner order gives:
        // reversing negates that difference exactly, so a mesh reversed here is never
        // reversed again when written and read back. (The sign of the total alone flipped
        // back and forth when huge coordinates left a total of rounding noise.)
        // The areas are taken in units of the largest coordinate (a power of two, exact):
        // near 1e-200 they underflowed to 0 and a clockwise mesh stayed clockwise.
        let unit = {
            let m = crate::numeric::largest_component(mesh.nodes.iter().flat_map(|p| [p.x, p.y]));
            let mut v = [DVec2::new(m, 0.0)];
            let f = crate::numeric::to_unit_scale(&mut v);
            f[0] * f[1]
        };
        let area_in = |e: usize, order: &[usize]| {
            let ids = mesh.element(e);
            polygon_area(order.iter().map(|&j| mesh.nodes[ids[j] as usize] * unit))
        };
        let forward: f64 =
            (0..mesh.conn.kinds.len()).map(|e| area_in(e, &[0, 1, 2, 3][..mesh.conn.kinds[e].corners()])).sum();
        let backward: f64 = (0..mesh.conn.kinds.len())
            .map(|e| area_in(e, &mesh.conn.kinds[e].reversed_order()[..mesh.conn.kinds[e].corners()]))
            .sum();
        if forward - backward < 0.0 {
            for e in 0..mesh.element_count() {
                mesh.reverse_element(e);
            }
        }
        let names = FileNames { lines: &self.elem_lines, nodes: &self.node_numbers, elements: &self.element_numbers };
        finish(mesh, names, self.fixed)
    }

    /// Builds what the file's triangles and quads make: a planar [`Mesh`] when its points
    /// lie in a plane (as [`build`](Self::build)), else the parts of a surface in 3D (the
    /// checks of a planar mesh, with its points as given, and why they are not planar).
    /// The tetrahedra are not looked at: see [`has_tets`](Self::has_tets).
    pub(crate) fn build_planar_or_surface(self) -> Result<Flat> {
        self.check()?;
        let why = match self.to_plane() {
            Err(Error::NotPlanar { node, line, max_distance, relative, .. }) => {
                // `node` is the file's number already
                let at = line.map_or(String::new(), |l| format!(" (line {l})"));
                format!(
                    "node {node}{at} lies {} off the plane of the mesh, {} times the size of its elements",
                    crate::error::shown_number(max_distance),
                    crate::error::shown_number(relative)
                )
            }
            flat => return self.planar(flat?).map(Flat::Planar),
        };
        let mut s = self.surface_parts()?;
        s.not_planar = Some(why);
        Ok(Flat::Surface(s))
    }

    /// The parts of a surface in 3D whatever its points (a generator's), checked as a
    /// planar mesh's are.
    pub(crate) fn build_surface_parts(self) -> Result<SurfaceParts> {
        self.check()?;
        self.surface_parts()
    }

    fn surface_parts(mut self) -> Result<SurfaceParts> {
        let points: Vec<glam::DVec3> = std::mem::take(&mut self.points).into_iter().map(glam::DVec3::from).collect();
        let n = points.len();
        let mesh = Mesh {
            plane: None,
            loaded_3d: None,
            target: None,
            given_fixed: None,
            sliding: None,
            nodes: vec![DVec2::ZERO; n],
            fixed: vec![false; n],
            conn: Arc::new(Connectivity {
                kinds: self.kinds,
                elem_start: self.elem_start,
                elem_nodes: self.elem_nodes,
                topo: Topology::default(),
                reversed: Vec::new(),
            }),
        };
        let flags_given = !matches!(self.fixed, FixedSpec::Boundary);
        let names = FileNames { lines: &self.elem_lines, nodes: &self.node_numbers, elements: &self.element_numbers };
        let mesh = finish(mesh, names, self.fixed)?;
        super::topology::check_fans(&mesh, names)?;
        Ok(SurfaceParts { points, mesh, element_numbers: self.element_numbers, flags_given, not_planar: None })
    }

    /// The checks every mesh passes, planar or surface: at least one element, finite
    /// coordinates the arithmetic can hold, node indices in range, no node twice in an element.
    fn check(&self) -> Result<()> {
        if self.kinds.is_empty() {
            return Err(Error::Empty(if self.points.is_empty() {
                "no nodes and no elements".into()
            } else {
                format!("{} nodes but no triangle or quad elements", self.points.len())
            }));
        }
        for (i, p) in self.points.iter().enumerate() {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(Error::node(
                    self.node_number(i),
                    self.line_of_node(i),
                    format!("coordinate is not a finite number: {p:?}"),
                ));
            }
            if let Some(why) = p.iter().find_map(|&c| beyond_arithmetic(c)) {
                return Err(Error::node(self.node_number(i), self.line_of_node(i), why));
            }
        }
        let n = self.points.len();
        for e in 0..self.kinds.len() {
            let ids = &self.elem_nodes[self.elem_start[e] as usize..self.elem_start[e + 1] as usize];
            for &i in ids {
                if i as usize >= n {
                    return Err(Error::element(
                        self.element_numbers.of(e),
                        self.line_of_elem(e),
                        format!("refers to node {} but the mesh has {} nodes", self.node_number(i as usize), n),
                    ));
                }
            }
            for a in 0..ids.len() {
                if ids[a + 1..].contains(&ids[a]) {
                    return Err(Error::element(
                        self.element_numbers.of(e),
                        self.line_of_elem(e),
                        format!("{} uses node {} twice", self.kinds[e].name(), self.node_number(ids[a] as usize)),
                    ));
                }
            }
        }
        Ok(())
    }

    /// 2D coordinates of the points: as given when every z is equal, else in the plane of
    /// the elements; refuses non-planar input naming the node farthest off, how far, and
    /// how that compares with the size of its elements. With them the plane to map them
    /// back into 3D (`None` when every z is 0), so writers put the mesh back where it was.
    ///
    /// The plane is fitted robustly, so that one node far off (a mistyped exponent) can
    /// neither tilt it nor hide behind the size it gives the mesh: its normal is the
    /// component-wise median of the elements' unit normals (each element one vote,
    /// whatever its size; signs aligned), and its offset the median of the nodes'
    /// offsets. Each node must then lie within [`PLANAR_TOLERANCE`] of the size of the
    /// largest element it belongs to (measured in the plane), or of its own coordinates'
    /// magnitude, whichever is larger: rounding in the file is excused, an outlier is not,
    /// however large the mesh around it.
    fn to_plane(&self) -> Result<(Vec<DVec2>, Option<Plane>)> {
        let z0 = self.points.first().map(|p| p[2]).unwrap_or(0.0);
        if self.points.iter().all(|p| p[2] == z0) {
            let plane = (z0 != 0.0).then_some(Plane {
                origin: glam::DVec3::new(0.0, 0.0, z0),
                u: glam::DVec3::X,
                w: glam::DVec3::Y,
            });
            return Ok((self.points.iter().map(|p| DVec2::new(p[0], p[1])).collect(), plane));
        }
        // Work in units of the largest coordinate magnitude, so that the cross products
        // and distances below neither overflow (coordinates near 1e200 once gave NaN
        // coordinates) nor underflow (near 1e-160, "no area") for any finite input.
        // The z values differ, so some coordinate is nonzero and the scale is positive.
        let scale = crate::numeric::largest_component(self.points.iter().flatten());
        let v = |p: &[f64; 3]| glam::DVec3::new(p[0] / scale, p[1] / scale, p[2] / scale);
        let elem = |e: usize| &self.elem_nodes[self.elem_start[e] as usize..self.elem_start[e + 1] as usize];
        // Each element's unit normal (Newell's method on its corner polygon, in units of
        // its own extent from its first corner, so that tiny elements do not underflow).
        let mut normals = Vec::with_capacity(self.kinds.len());
        for e in 0..self.kinds.len() {
            let ids = elem(e);
            let k = self.kinds[e].corners();
            let o = v(&self.points[ids[0] as usize]);
            let extent = crate::numeric::largest_component(ids[..k].iter().map(|&i| v(&self.points[i as usize]) - o));
            if extent == 0.0 {
                continue;
            }
            let mut n = glam::DVec3::ZERO;
            for i in 0..k {
                let a = (v(&self.points[ids[i] as usize]) - o) / extent;
                let b = (v(&self.points[ids[(i + 1) % k] as usize]) - o) / extent;
                n += a.cross(b);
            }
            if norm(n) > 1e-12 {
                normals.push(n / norm(n));
            }
        }
        if normals.is_empty() {
            return Err(Error::invalid("cannot find the plane of the mesh: its elements have no area"));
        }
        // Two rounds: align the signs to a guess, take the median, align to that.
        let mut normal = normals[0];
        for _ in 0..2 {
            let aligned = |c: usize| normals.iter().map(move |n| if n.dot(normal) < 0.0 { -n[c] } else { n[c] });
            let m = glam::DVec3::new(
                median(aligned(0).collect()),
                median(aligned(1).collect()),
                median(aligned(2).collect()),
            );
            if norm(m) > 0.0 {
                normal = m / norm(m);
            }
        }
        // The mesh faces +normal where its elements do by area (Newell over all of them),
        // so that elements come out counter-clockwise as they were drawn.
        let mut facing = 0.0;
        for e in 0..self.kinds.len() {
            let ids = elem(e);
            let k = self.kinds[e].corners();
            for i in 0..k {
                facing +=
                    v(&self.points[ids[i] as usize]).cross(v(&self.points[ids[(i + 1) % k] as usize])).dot(normal);
            }
        }
        if facing < 0.0 {
            normal = -normal;
        }
        let offset = median(self.points.iter().map(|p| v(p).dot(normal)).collect());
        // In-plane basis (u, w) with u × w = normal.
        let helper = if normal.x.abs() < 0.9 { glam::DVec3::X } else { glam::DVec3::Y };
        let u = (helper - normal * helper.dot(normal)).normalize();
        let w = normal.cross(u);
        let centre = normal * offset;
        let flat: Vec<DVec2> =
            self.points.iter().map(|p| v(p) - centre).map(|d| DVec2::new(d.dot(u), d.dot(w))).collect();
        // Each node's size: the largest element it belongs to, in the plane (the diagonal
        // of the element's bounding box there). Unused nodes get the largest element's.
        let mut size = vec![0.0f64; self.points.len()];
        let mut largest = 0.0f64;
        for e in 0..self.kinds.len() {
            let ids = elem(e);
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            for &i in ids {
                lo = lo.min(flat[i as usize]);
                hi = hi.max(flat[i as usize]);
            }
            let d = (hi - lo).length();
            largest = largest.max(d);
            for &i in ids {
                size[i as usize] = size[i as usize].max(d);
            }
        }
        let mut worst: Option<(usize, f64, f64)> = None;
        for (i, p) in self.points.iter().enumerate() {
            let distance = (v(p).dot(normal) - offset).abs();
            let own = if size[i] > 0.0 { size[i] } else { largest };
            let allowed = PLANAR_TOLERANCE * own.max(v(p).abs().max_element()).max(centre.abs().max_element());
            if distance > allowed && worst.map_or(true, |(_, d, _)| distance > d) {
                worst = Some((i, distance, own));
            }
        }
        if let Some((node, distance, own)) = worst {
            return Err(Error::NotPlanar {
                node: self.node_number(node),
                line: self.line_of_node(node),
                max_distance: distance * scale,
                relative: if own > 0.0 { distance / own } else { f64::INFINITY },
                tolerance: PLANAR_TOLERANCE,
            });
        }
        let mut out = Vec::with_capacity(self.points.len());
        for (i, q) in flat.iter().enumerate() {
            let q = *q * scale;
            if !q.is_finite() {
                return Err(Error::node(
                    self.node_number(i),
                    self.line_of_node(i),
                    format!(
                        "its coordinates in the plane of the mesh are too large for a 64-bit float: {:?}",
                        self.points[i]
                    ),
                ));
            }
            out.push(q);
        }
        Ok((out, Some(Plane { origin: centre * scale, u, w })))
    }
}

/// The last step of building any mesh: the topology from the elements (with the lines
/// and numbers of the file for its errors) and the fixed flags as `fixed` says; nodes no element
/// uses never move.
pub(super) fn finish(mut mesh: Mesh, names: FileNames<'_>, fixed: FixedSpec) -> Result<Mesh> {
    let n = mesh.nodes.len();
    let topo = build_topology(&mesh, names)?;
    mesh.connectivity_mut().topo = topo;
    let boundary = mesh.conn.topo.boundary.clone();
    mesh.given_fixed = match &fixed {
        FixedSpec::Boundary => None,
        FixedSpec::Exact(f) | FixedSpec::BoundaryAnd(f) => {
            let mut flags = f.clone();
            flags.resize(n, false);
            Some(Arc::new(super::GivenFlags { flags, exact: matches!(fixed, FixedSpec::Exact(_)) }))
        }
    };
    mesh.fixed = match fixed {
        FixedSpec::Boundary => boundary,
        FixedSpec::Exact(f) => {
            if f.len() != n {
                return Err(Error::invalid(format!("{} fixed flags for {} nodes", f.len(), n)));
            }
            f
        }
        FixedSpec::BoundaryAnd(f) => {
            boundary.iter().zip(f.iter().chain(std::iter::repeat(&false))).map(|(a, b)| *a || *b).collect()
        }
    };
    // Nodes no element uses never move.
    for i in 0..n {
        if mesh.conn.topo.role[i] == NodeRole::Unused {
            mesh.fixed[i] = true;
        }
    }
    Ok(mesh)
}

/// The median of the values (the upper one of the middle two for an even count); NaN-free
/// input.
fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mid = values.len() / 2;
    *values.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// Euclidean length without underflow or overflow of the squares (scaled by the
/// largest component first).
fn norm(v: glam::DVec3) -> f64 {
    let m = v.abs().max_element();
    if m > 0.0 && m.is_finite() {
        m * (v / m).length()
    } else {
        m
    }
}
