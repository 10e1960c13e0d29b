//! The reference surface a surface mesh's nodes stay on: the mesh as it was loaded, as
//! flat triangles ([`Facets`]), or an exact analytic surface a generator knows
//! ([`Analytic`]). A moved node is projected back onto it by [`Reference::project`].

use glam::DVec3;

use crate::mesh::{ElementKind, NONE};
use crate::numeric::order::{pair_key, sort_stable_by_key};

mod fitted;
mod grid;
mod patch;

pub use fitted::Fitted;

use grid::Grid;
use patch::Patch;

/// Where a point projects onto the reference: the nearest point found, the reference's
/// unit normal there (oriented as the mesh's elements), and the facet it lies on (for an
/// analytic surface, the smooth part), which starts the next search for the same node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    pub point: DVec3,
    pub normal: DVec3,
    pub face: u32,
}

/// The surface nodes are projected onto.
#[derive(Clone, Debug)]
pub enum Reference {
    /// The loaded mesh's elements as flat triangles (see [`Facets`]).
    Facets(Box<Facets>),
    /// A surface fitted through the loaded mesh's nodes, where its elements are folded (a
    /// tangled file; see [`Fitted`]).
    Fitted(Box<Fitted>),
    /// An exact surface (generated samples).
    Analytic(Analytic),
}

impl Reference {
    /// The nearest point of the reference to `p` on the smooth part `hint` lies on (a
    /// node's last projection's facet, or for an analytic surface its part), searched
    /// from there; anywhere when `hint` is [`NONE`]. A node never crosses a feature curve.
    pub fn project(&self, p: DVec3, hint: u32) -> Projected {
        match self {
            Reference::Facets(f) => f.project(p, hint),
            Reference::Fitted(f) => f.project(p, hint),
            Reference::Analytic(a) => a.project(p, hint),
        }
    }
    /// A hint ([`project`](Self::project)) on element `e`'s own smooth part, where the
    /// reference knows the elements: the first facet of `e` for a loaded mesh; `None` for
    /// an analytic surface (its parts are found from the point).
    pub fn element_hint(&self, e: usize) -> Option<u32> {
        match self {
            Reference::Facets(f) => f.first_triangle.get(e).copied(),
            Reference::Fitted(f) => f.element_fit(e),
            Reference::Analytic(_) => None,
        }
    }
    /// What the reference is, in words (for `stats`).
    pub fn describe(&self) -> String {
        match self {
            Reference::Facets(f) => format!("the loaded mesh, {} flat triangles", f.triangles.len()),
            Reference::Fitted(f) => {
                format!("fitted through the loaded mesh's nodes (its elements are folded), {} quadrics", f.fit_count())
            }
            Reference::Analytic(a) => a.describe(),
        }
    }
}

/// An exact surface, with its closest point and normal in closed form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Analytic {
    /// The sphere of `radius` about `centre`, normal outward.
    Sphere { centre: DVec3, radius: f64 },
    /// The cylinder of `radius` about the z axis from `z0` to `z1`, closed by flat caps
    /// (normal outward on the side and the caps). A point projects onto the nearest part.
    CappedCylinder { radius: f64, z0: f64, z1: f64 },
    /// The torus about the z axis: tube of radius `minor` round the circle of radius
    /// `major` in the plane z = 0, normal outward.
    Torus { major: f64, minor: f64 },
}

impl Analytic {
    fn describe(&self) -> String {
        match *self {
            Analytic::Sphere { radius, .. } => format!("a sphere of radius {radius}"),
            Analytic::CappedCylinder { radius, z0, z1 } => {
                format!("a cylinder of radius {radius} from z = {z0} to {z1}, with caps")
            }
            Analytic::Torus { major, minor } => format!("a torus of radii {major} and {minor}"),
        }
    }

    /// Whether the surface point `p` lies on a feature curve: the capped cylinder's rims.
    pub fn on_feature(&self, p: DVec3) -> bool {
        match *self {
            Analytic::CappedCylinder { radius, z0, z1 } => {
                let on_side = (DVec3::new(p.x, p.y, 0.0).length() - radius).abs() <= 1e-9 * radius;
                let on_cap = (p.z - z0).abs() <= 1e-9 * (z1 - z0) || (p.z - z1).abs() <= 1e-9 * (z1 - z0);
                on_side && on_cap
            }
            _ => false,
        }
    }

    /// The smooth part of the surface point `p` lies on: for the capped cylinder 0 the
    /// side, 1 the bottom cap, 2 the top (a rim point: the side); 0 for the others.
    pub fn part_of(&self, p: DVec3) -> u32 {
        match *self {
            Analytic::CappedCylinder { radius, z0, z1 } => {
                let on_side = (DVec3::new(p.x, p.y, 0.0).length() - radius).abs() <= 1e-9 * radius;
                if on_side {
                    0
                } else if (p.z - z0).abs() <= (p.z - z1).abs() {
                    1
                } else {
                    2
                }
            }
            _ => 0,
        }
    }

    /// The nearest point of part `part` of the surface to `p` (of the whole surface for
    /// [`NONE`]) and the outward normal there.
    pub fn project(&self, p: DVec3, part: u32) -> Projected {
        let (point, normal, part) = match *self {
            Analytic::Sphere { centre, radius } => {
                let n = (p - centre).try_normalize().unwrap_or(DVec3::Z);
                (centre + n * radius, n, 0)
            }
            Analytic::CappedCylinder { radius, z0, z1 } => {
                let radial = DVec3::new(p.x, p.y, 0.0).try_normalize().unwrap_or(DVec3::X);
                let r = DVec3::new(p.x, p.y, 0.0).length().min(radius);
                let parts = [
                    (radial * radius + DVec3::Z * p.z.clamp(z0, z1), radial),
                    (radial * r + DVec3::Z * z0, -DVec3::Z),
                    (radial * r + DVec3::Z * z1, DVec3::Z),
                ];
                let d = |i: usize| (parts[i].0 - p).length_squared();
                let i = match part {
                    0..=2 => part as usize,
                    _ => (0..3).min_by(|&a, &b| d(a).total_cmp(&d(b))).unwrap_or(0),
                };
                (parts[i].0, parts[i].1, i as u32)
            }
            Analytic::Torus { major, minor } => {
                let radial = DVec3::new(p.x, p.y, 0.0).try_normalize().unwrap_or(DVec3::X);
                let ring = radial * major;
                let n = (p - ring).try_normalize().unwrap_or(radial);
                (ring + n * minor, n, 0)
            }
        };
        Projected { point, normal, face: part }
    }
}

/// The loaded mesh as flat triangles: a linear triangle is one, a quad two (split along
/// its diagonal 0–2), a 6-node triangle four and a quadratic quad eight (about its centre
/// node, or for the 8-node quad the serendipity centre), through the mid-side nodes.
/// Vertices are the mesh's node numbers, plus one added point per 8-node quad. The flat
/// triangles find where a point is; on a surface of quadratic elements, their curved
/// patches (their shape functions through their nodes, `Patch`) then give the point —
/// unless an element of the file is folded (a tangled file), whose patches fold over
/// themselves: then the flat triangles through every node are the reference.
#[derive(Clone, Debug)]
pub struct Facets {
    points: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    /// Per triangle, the smooth part of the surface it belongs to (its element's part:
    /// parts meet at feature curves).
    part: Vec<u32>,
    /// Per vertex, the unit normal of its triangles (their normals summed, each weighted
    /// by its area), interpolated across a triangle for the normal at a point: smooth
    /// over the facets, and right where one facet of a tangled file is turned over.
    vertex_normal: Vec<DVec3>,
    /// The same for a vertex on a feature curve, per smooth part: keyed by (vertex, part),
    /// sorted. A point of a facet takes its own part's normals, not a blend across the
    /// curve: three faces of a solid meeting at a corner (or two at an edge turning past a
    /// right angle) have area-weighted sums that face away from one of them, and a strip
    /// folded back on itself would average its two sheets' normals to nothing.
    part_normal: Vec<((u32, u32), DVec3)>,
    /// Per triangle of a quadratic element, its element's curved patch and where the
    /// triangle's vertices are in the patch's parameters (all `None` when the patches are
    /// not used: linear elements, or a folded one in the file).
    patch: Vec<Option<(u32, [[f64; 2]; 3])>>,
    patches: Vec<Patch>,
    /// Per element of the loaded mesh, its first triangle (an element's triangles are
    /// consecutive).
    first_triangle: Vec<u32>,
    /// Whether an element of the file is folded: a flat triangle whose normal disagrees
    /// with one of its vertices' (then the patches are not used, and a surface is fitted
    /// through the nodes instead, [`Fitted`]).
    folded: bool,
    /// Vertex → triangles (CSR), for the walk.
    vert_start: Vec<u32>,
    vert_tris: Vec<u32>,
    grid: Grid,
}

/// The area vector of triangle `t` of `pts` (twice its area, along its normal), of its
/// edges multiplied by `unit` (a power of two bringing extreme scales to unit size; 1
/// inside 2^±200).
fn area_vector(pts: &[DVec3], t: &[u32; 3], unit: f64) -> DVec3 {
    let [a, b, c] = t.map(|v| pts[v as usize]);
    if unit == 1.0 {
        (b - a).cross(c - a)
    } else {
        ((b - a) * unit).cross((c - a) * unit)
    }
}

/// Steps the walk takes before the spatial index is asked instead.
const MAX_WALK: usize = 256;

/// Steps of the search for a direction that sees all of a vertex's triangles from outside
/// ([`Facets::sees_from_outside`]): it finds one whose worst triangle is seen at more than
/// about 1/√steps radians (3.6° for 256), when there is one.
const MAX_SEE_STEPS: usize = 256;

/// The unit normals of the triangles round each vertex whose triangles carry more than
/// one key (`key`, per triangle: its smooth part, or its side of the folds), per key:
/// their area vectors (`area`) summed, keyed by (vertex, key), sorted.
fn keyed_normals(
    triangles: &[[u32; 3]],
    key: &[u32],
    vertices: usize,
    area: impl Fn(&[u32; 3]) -> DVec3,
) -> Vec<((u32, u32), DVec3)> {
    let mut first = vec![u32::MAX; vertices];
    let mut mixed = vec![false; vertices];
    for (tri, &k) in triangles.iter().zip(key) {
        for &v in tri {
            let f = &mut first[v as usize];
            mixed[v as usize] |= *f != u32::MAX && *f != k;
            *f = k;
        }
    }
    let mut keyed: Vec<((u32, u32), DVec3)> = Vec::new();
    for (tri, &k) in triangles.iter().zip(key) {
        let n = area(tri);
        keyed.extend(tri.iter().filter(|&&v| mixed[v as usize]).map(|&v| ((v, k), n)));
    }
    sort_stable_by_key(&mut keyed, |&((v, k), _)| pair_key(v, k));
    keyed.dedup_by(|(k1, n1), (k0, n0)| {
        let same = k1 == k0;
        if same {
            *n0 += *n1;
        }
        same
    });
    for (_, n) in &mut keyed {
        *n = crate::numeric::direction(*n);
    }
    keyed
}

/// The unit normal at vertex `v` of its triangles with key `k`: from `keyed`
/// ([`keyed_normals`]) where its triangles carry several keys, else `vertex_normal`.
fn keyed_normal(keyed: &[((u32, u32), DVec3)], vertex_normal: &[DVec3], v: u32, k: u32) -> DVec3 {
    match keyed.binary_search_by_key(&(v, k), |&(key, _)| key) {
        Ok(i) => keyed[i].1,
        Err(_) => vertex_normal[v as usize],
    }
}

impl Facets {
    /// The facets of the elements (`kinds`, each element's nodes by `element`, its smooth
    /// part by `part`) over `points`.
    pub fn new<'a>(
        points: &[DVec3],
        kinds: &[ElementKind],
        element: impl Fn(usize) -> &'a [u32],
        part: impl Fn(usize) -> u32,
        side: impl Fn(usize) -> u32,
    ) -> Facets {
        let mut pts = points.to_vec();
        let mut triangles = Vec::with_capacity(kinds.len() * 2);
        let mut parts = Vec::with_capacity(kinds.len() * 2);
        let mut sides = Vec::with_capacity(kinds.len() * 2);
        let (mut patch, mut patches) = (Vec::with_capacity(kinds.len() * 2), Vec::new());
        let mut first_triangle = Vec::with_capacity(kinds.len());
        for (e, &kind) in kinds.iter().enumerate() {
            let ids = element(e);
            first_triangle.push(triangles.len() as u32);
            match kind {
                ElementKind::Tri3 => triangles.push([ids[0], ids[1], ids[2]]),
                ElementKind::Quad4 => {
                    triangles.push([ids[0], ids[1], ids[2]]);
                    triangles.push([ids[0], ids[2], ids[3]]);
                }
                ElementKind::Tri6 => {
                    let [a, b, c, ab, bc, ca] = [ids[0], ids[1], ids[2], ids[3], ids[4], ids[5]];
                    triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
                }
                ElementKind::Quad8 | ElementKind::Quad9 => {
                    let centre = if kind == ElementKind::Quad9 {
                        ids[8]
                    } else {
                        // the serendipity quad's centre: −¼ Σ corners + ½ Σ mid-sides
                        let c: DVec3 =
                            (0..4).map(|i| -0.25 * pts[ids[i] as usize] + 0.5 * pts[ids[4 + i] as usize]).sum();
                        pts.push(c);
                        (pts.len() - 1) as u32
                    };
                    for i in 0..4 {
                        let (c0, m, c1) = (ids[i], ids[4 + i], ids[(i + 1) % 4]);
                        triangles.push([c0, m, centre]);
                        triangles.push([m, c1, centre]);
                    }
                }
            }
            if kind.is_quadratic() {
                let mut nodes = [0u32; 9];
                nodes[..kind.node_count()].copy_from_slice(ids);
                let p = Patch { kind, nodes };
                let k = patches.len() as u32;
                patch.extend(p.triangle_parameters().into_iter().map(|uv| Some((k, uv))));
                patches.push(p);
            } else {
                patch.resize(triangles.len(), None);
            }
            debug_assert_eq!(patch.len(), triangles.len());
            parts.resize(triangles.len(), part(e));
            sides.resize(triangles.len(), side(e));
        }
        let mut vert_start = vec![0u32; pts.len() + 1];
        for t in &triangles {
            for &v in t {
                vert_start[v as usize + 1] += 1;
            }
        }
        for i in 0..pts.len() {
            vert_start[i + 1] += vert_start[i];
        }
        let mut fill = vert_start.clone();
        let mut vert_tris = vec![0u32; triangles.len() * 3];
        for (t, tri) in triangles.iter().enumerate() {
            for &v in tri {
                vert_tris[fill[v as usize] as usize] = t as u32;
                fill[v as usize] += 1;
            }
        }
        let grid = Grid::new(&pts, &triangles);
        // the facets' area vectors, in units of the largest edge where the edges are
        // beyond 2^±200 (one power of two for all, so the area weights stay; as given
        // inside it): a sphere of 1e80 has cross products whose squares leave the doubles
        let reach = crate::numeric::largest_component(triangles.iter().flat_map(|t| {
            let [a, b, c] = t.map(|v| pts[v as usize]);
            [b - a, c - a]
        }));
        let unit = match crate::numeric::factors_beyond_safe_scale(reach) {
            None => 1.0,
            Some((f1, f2)) => f1 * f2,
        };
        let area = |t: &[u32; 3]| area_vector(&pts, t, unit);
        let mut vertex_normal = vec![DVec3::ZERO; pts.len()];
        for t in &triangles {
            let n = area(t);
            for &v in t {
                vertex_normal[v as usize] += n;
            }
        }
        for n in &mut vertex_normal {
            *n = crate::numeric::direction(*n);
        }
        let part_normal = keyed_normals(&triangles, &parts, pts.len(), area);
        let side_normal = keyed_normals(&triangles, &sides, pts.len(), area);
        let mut facets = Facets {
            points: pts,
            triangles,
            part: parts,
            vertex_normal,
            part_normal,
            patch,
            patches,
            first_triangle,
            folded: false,
            vert_start,
            vert_tris,
            grid,
        };
        // a folded element: a flat triangle whose normal disagrees with a vertex's there, on
        // its side of the folds that are feature curves. Across a crease that normal is a
        // blend of the parts', which past a right angle may face away from one of them
        // though nothing folds (a sharp corner or edge of a solid): where the vertex is on
        // a crease, the triangle is folded only if it disagrees with its own part's normal
        // too, or if no direction sees the vertex's triangles on its side all from outside
        // (a fan folded over itself)
        let folded = (0..facets.triangles.len()).any(|t| {
            let tri = facets.triangles[t];
            let n = area_vector(&facets.points, &tri, unit);
            tri.iter().any(|&v| {
                let k = sides[t];
                n.dot(keyed_normal(&side_normal, &facets.vertex_normal, v, k)) <= 0.0
                    && (n.dot(facets.vertex_normal_on(v, facets.part[t])) <= 0.0
                        || !facets.sees_from_outside(v, |u| sides[u as usize] == k))
            })
        });
        if folded {
            facets.patch.iter_mut().for_each(|p| *p = None);
        }
        facets.folded = folded;
        facets
    }

    /// The facets with a point's normal blended across the feature curves (its
    /// triangle's vertices' normals of all their triangles), as a volume's skin has it: its
    /// surface nodes slide in the tangent planes so blended near the curves, which its
    /// measurements were taken with (Livesu et al.'s block stress test untangles so, and
    /// keeps 3 elements inverted with each part's own normals).
    pub fn with_normals_across_parts(mut self) -> Facets {
        self.part_normal = Vec::new();
        self
    }

    /// Whether an element of the file is folded: a flat triangle whose normal disagrees
    /// with one of its vertices' (then a surface is fitted through the nodes, [`Fitted`]).
    pub fn is_folded(&self) -> bool {
        self.folded
    }

    /// The unit normal at vertex `v` of its triangles on smooth part `k`
    /// ([`Facets::part_normal`] where it lies on a feature curve, else
    /// [`Facets::vertex_normal`]).
    fn vertex_normal_on(&self, v: u32, k: u32) -> DVec3 {
        keyed_normal(&self.part_normal, &self.vertex_normal, v, k)
    }

    /// Whether some direction sees every triangle round vertex `v` that `take`s from
    /// outside (each triangle's normal within a right angle of it): a sharp corner's faces
    /// turn past a right angle from one another and are seen so, a fan folded over itself
    /// is not. Sought by the perceptron's rule from the normal of all of them: add the
    /// normal of the triangle seen worst, at most [`MAX_SEE_STEPS`] times.
    fn sees_from_outside(&self, v: u32, take: impl Fn(u32) -> bool) -> bool {
        let normals: Vec<DVec3> =
            self.around(v as usize).iter().filter(|&&t| take(t)).map(|&t| self.normal(t)).filter(|n| *n != DVec3::ZERO).collect();
        let mut d = self.vertex_normal[v as usize];
        for _ in 0..MAX_SEE_STEPS {
            let worst = normals.iter().min_by(|a, b| d.dot(**a).total_cmp(&d.dot(**b)));
            match worst {
                Some(&n) if d.dot(n) <= 0.0 => d += n,
                _ => return true,
            }
        }
        false
    }

    /// A triangle with vertex `v`, to start the walk from a node where it was loaded
    /// ([`NONE`] when no triangle has it).
    pub fn triangle_at_vertex(&self, v: usize) -> u32 {
        self.around(v).first().copied().unwrap_or(NONE)
    }

    fn around(&self, v: usize) -> &[u32] {
        match (self.vert_start.get(v), self.vert_start.get(v + 1)) {
            (Some(&a), Some(&b)) => &self.vert_tris[a as usize..b as usize],
            _ => &[],
        }
    }

    fn corners(&self, t: u32) -> [DVec3; 3] {
        self.triangles[t as usize].map(|v| self.points[v as usize])
    }

    /// The unit normal of triangle `t` (zero for a degenerate one).
    fn normal(&self, t: u32) -> DVec3 {
        let [a, b, c] = self.corners(t);
        let [u, v] = crate::numeric::in_unit_scale_3d([b - a, c - a]);
        crate::numeric::direction(u.cross(v))
    }

    /// The nearest point of the facets to `p`: a walk from `hint` over neighbouring
    /// triangles while the distance falls (the local nearest point, which for a node
    /// moved within its star is the one meant), else the spatial index's global nearest.
    pub fn project(&self, p: DVec3, hint: u32) -> Projected {
        let part = self.part.get(hint as usize).copied();
        if part.is_some() {
            if let Some(t) = self.walk(p, hint) {
                return self.projected(p, t);
            }
        }
        let t = self.grid.nearest(p, |t| match part {
            Some(k) if self.part[t as usize] != k => None,
            _ => Some(closest_on_triangle(p, self.corners(t)).0),
        });
        self.projected(p, t)
    }

    fn projected(&self, p: DVec3, t: u32) -> Projected {
        if t == NONE {
            return Projected { point: p, normal: DVec3::Z, face: NONE };
        }
        if self.patch[t as usize].is_some() {
            return self.on_patches(p, t);
        }
        let (point, bary) = closest_on_triangle(p, self.corners(t));
        let tri = self.triangles[t as usize];
        let blended: DVec3 = (0..3).map(|i| bary[i] * self.vertex_normal_on(tri[i], self.part[t as usize])).sum();
        let normal = Some(crate::numeric::direction(blended)).filter(|n| *n != DVec3::ZERO).unwrap_or_else(|| self.normal(t));
        Projected { point, normal, face: t }
    }

    /// The nearest point of the patches of the triangles round `t` (the flat triangle
    /// nearest `p`), each patch once, from its nearest flat triangle's point: a curved
    /// patch bulges past its flat triangles, so a point of one patch may be nearest a flat
    /// triangle of the next, and a point on a patch must project onto itself.
    fn on_patches(&self, p: DVec3, t: u32) -> Projected {
        let mut seen: Vec<u32> = Vec::with_capacity(16);
        let mut best: Option<(f64, DVec3, DVec3, u32)> = None;
        let near = std::iter::once(t)
            .chain(self.triangles[t as usize].iter().flat_map(|&v| self.around(v as usize).iter().copied()));
        for u in near.filter(|&u| self.part[u as usize] == self.part[t as usize]) {
            let Some((k, uv)) = self.patch[u as usize] else { continue };
            if seen.contains(&k) {
                continue;
            }
            seen.push(k);
            let (_, bary) = closest_on_triangle(p, self.corners(u));
            let start = [0, 1].map(|j| (0..3).map(|i| bary[i] * uv[i][j]).sum::<f64>());
            let (point, normal) = self.patches[k as usize].nearest(&self.points, p, start);
            let d = (point - p).length_squared();
            if best.map_or(true, |b| d < b.0) {
                best = Some((d, point, normal, u));
            }
        }
        let (_, point, normal, face) = best.expect("the triangle's own patch");
        Projected { point, normal, face }
    }

    /// The walk: from triangle `t`, go to the nearest of the triangles that share a
    /// vertex with it while that one is strictly nearer to `p`. (Across edges alone, a
    /// point could stop on a face it lies behind, a local nearest point on the far side
    /// of a thin or sharp part.) `None` when it has not settled within [`MAX_WALK`] steps.
    fn walk(&self, p: DVec3, mut t: u32) -> Option<u32> {
        let dist = |t: u32| (closest_on_triangle(p, self.corners(t)).0 - p).length_squared();
        let part = self.part[t as usize];
        let mut d = dist(t);
        for _ in 0..MAX_WALK {
            let mut best = (d, t);
            for &v in &self.triangles[t as usize] {
                for &u in self.around(v as usize) {
                    if u != best.1 && self.part[u as usize] == part {
                        let du = dist(u);
                        if du < best.0 {
                            best = (du, u);
                        }
                    }
                }
            }
            if best.1 == t {
                return Some(t);
            }
            (d, t) = best;
        }
        None
    }
}

/// The nearest point of triangle `[a, b, c]` to `p` and its barycentric weights (Ericson,
/// *Real-Time Collision Detection*, §5.1.5): a weight is exactly 0 where the point lies on
/// the opposite edge.
pub fn closest_on_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> (DVec3, [f64; 3]) {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, [1.0, 0.0, 0.0]);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, [0.0, 1.0, 0.0]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, [1.0 - v, v, 0.0]);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, [0.0, 0.0, 1.0]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, [1.0 - w, 0.0, w]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, [0.0, 1.0 - w, w]);
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    if !(v.is_finite() && w.is_finite()) {
        // a degenerate triangle: its nearest corner
        let best = [a, b, c].into_iter().enumerate().min_by(|x, y| (x.1 - p).length().total_cmp(&(y.1 - p).length()));
        let (i, q) = best.expect("three corners");
        let mut bary = [0.0; 3];
        bary[i] = 1.0;
        return (q, bary);
    }
    (a + ab * v + ac * w, [1.0 - v - w, v, w])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_point_regions_by_hand() {
        let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
        // above the face: straight down, all weights positive
        let (q, w) = closest_on_triangle(DVec3::new(0.25, 0.25, 3.0), tri);
        assert_eq!(q, DVec3::new(0.25, 0.25, 0.0));
        assert!(w.iter().all(|&x| x > 0.0));
        // beyond the corner a: a
        assert_eq!(closest_on_triangle(DVec3::new(-1.0, -1.0, 1.0), tri), (DVec3::ZERO, [1.0, 0.0, 0.0]));
        // beyond the edge a–b: onto it, the weight of c zero
        let (q, w) = closest_on_triangle(DVec3::new(0.5, -2.0, 0.0), tri);
        assert_eq!(q, DVec3::new(0.5, 0.0, 0.0));
        assert_eq!(w, [0.5, 0.5, 0.0]);
        // beyond the hypotenuse
        let (q, w) = closest_on_triangle(DVec3::new(1.0, 1.0, 0.0), tri);
        assert!((q - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15 && w[0] == 0.0);
    }

    /// An octahedron of radius 1 as facets.
    fn octahedron() -> Facets {
        let p = [DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y, DVec3::Z, -DVec3::Z];
        let tris: Vec<[u32; 3]> = (0..4u32).flat_map(|i| [[i, (i + 1) % 4, 4], [(i + 1) % 4, i, 5]]).collect();
        let flat: Vec<u32> = tris.iter().flatten().copied().collect();
        Facets::new(&p, &[ElementKind::Tri3; 8], |e| &flat[3 * e..3 * e + 3], |_| 0, |_| 0)
    }

    #[test]
    fn the_walk_and_the_grid_find_the_same_nearest_point() {
        let f = octahedron();
        let mut rng = crate::numeric::SplitMix64::new(7);
        let mut coordinate = || 4.0 * rng.next_f64() - 2.0;
        for i in 0..1000 {
            // half the points anywhere, half near the surface (a node moved in its star)
            let mut p = DVec3::new(coordinate(), coordinate(), coordinate());
            if i % 2 == 1 {
                let q = p / p.abs().element_sum();
                p = q + 0.1 * DVec3::new(coordinate(), coordinate(), coordinate());
            }
            let global = f.project(p, NONE);
            // brute force
            let brute =
                (0..8u32).map(|t| (closest_on_triangle(p, f.corners(t)).0 - p).length()).fold(f64::INFINITY, f64::min);
            assert!(((global.point - p).length() - brute).abs() < 1e-12, "{p}");
            // from every triangle that shares a vertex with the one it lands on (a node's
            // last facet, for a node moved within its star), the walk finds it too; from
            // the far side it may stop on a ridge facing away, a local nearest point
            if i % 2 == 0 {
                continue;
            }
            let near = f.triangles[global.face as usize];
            for hint in (0..8u32).filter(|&t| f.triangles[t as usize].iter().any(|v| near.contains(v))) {
                let walked = f.project(p, hint);
                assert!(((walked.point - p).length() - brute).abs() < 1e-12, "{p} from {hint}");
            }
        }
    }

    /// The right-corner tetrahedron (the origin and the three unit points), outward.
    fn right_corner_tetrahedron(part: [u32; 4]) -> Facets {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let flat = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3];
        Facets::new(&p, &[ElementKind::Tri3; 4], |e| &flat[3 * e..3 * e + 3], |e| part[e], |_| 0)
    }

    /// At the corner (1, 0, 0) of the right-corner tetrahedron the area vectors of its
    /// three faces, −z, −y and (1, 1, 1) (the slanted face's twice area √3 along its unit
    /// normal), sum to +x, at a right angle to the two right faces: across the edges the
    /// blend faces neither way. Read as one smooth part, the solid is folded; with its
    /// edges as feature curves each face is a part, every point of a face has the face's
    /// normal, and nothing is folded (a direction sees the three faces from outside).
    #[test]
    fn a_sharp_corner_is_not_a_fold_and_takes_its_own_faces_normals() {
        assert!(right_corner_tetrahedron([0; 4]).is_folded(), "one part: the blend faces away");
        let f = right_corner_tetrahedron([0, 1, 2, 3]);
        assert!(!f.is_folded());
        let s = 3f64.sqrt().recip();
        let faces = [
            (0.25 * (DVec3::X + DVec3::Y), -DVec3::Z),
            (0.25 * (DVec3::X + DVec3::Z), -DVec3::Y),
            (0.25 * (DVec3::Y + DVec3::Z), -DVec3::X),
            (DVec3::splat(1.0 / 3.0), DVec3::splat(s)),
        ];
        for (t, (centre, normal)) in faces.into_iter().enumerate() {
            // a point of the face, its corners and a point on each edge
            let [a, b, c] = f.corners(t as u32);
            for p in [centre, a, b, c, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)] {
                let q = f.project(p, t as u32);
                assert!((q.normal - normal).length() < 1e-15, "face {t} at {p}: {}", q.normal);
            }
        }
    }

    /// A fan of six triangles round a vertex in a plane, one of them turned over: it is
    /// folded whether its edges are read as creases (each triangle a part of its own, as a
    /// tangle's angles would make them) or not, since no direction sees both +z and −z
    /// from outside.
    #[test]
    fn a_turned_triangle_is_folded_even_between_creases() {
        let mut p = vec![DVec3::ZERO];
        p.extend((0..6).map(|i| {
            let a = i as f64 * std::f64::consts::FRAC_PI_3;
            DVec3::new(libm::cos(a), libm::sin(a), 0.0)
        }));
        let mut flat: Vec<u32> = (0..6u32).flat_map(|i| [0, 1 + i, 1 + (i + 1) % 6]).collect();
        flat.swap(3 * 2 + 1, 3 * 2 + 2);
        for parts in [[0; 6], [0, 1, 2, 3, 4, 5]] {
            let f = Facets::new(&p, &[ElementKind::Tri3; 6], |e| &flat[3 * e..3 * e + 3], |e| parts[e], |_| 0);
            assert!(f.is_folded(), "parts {parts:?}");
        }
    }

    /// A quadratic reference is its elements' curved patches: its nodes project onto
    /// themselves, and points of the exact sphere a quadratic cube-sphere stands for are
    /// much nearer its patches than its flat triangles (13–16 times at resolution 8).
    #[test]
    fn quadratic_elements_are_curved_patches_of_the_reference() {
        use crate::generate::{surface, SurfaceKind, SurfaceShape};
        for kind in SurfaceKind::ALL {
            let s = surface(SurfaceShape::Sphere, kind, 2, 8).unwrap();
            let mesh = s.flat();
            let facets = Facets::new(s.points(), mesh.kinds(), |e| mesh.element(e), |_| 0, |_| 0);
            assert!(facets.patch.iter().all(|p| p.is_some()), "an untangled file: its patches");
            let mut flat = facets.clone();
            flat.patch.iter_mut().for_each(|p| *p = None);
            for (n, &p) in s.points().iter().enumerate() {
                let q = facets.project(p, facets.triangle_at_vertex(n));
                assert!((q.point - p).length() < 1e-14, "node {n} moved {}", (q.point - p).length());
            }
            let (mut curved, mut straight) = (0.0f64, 0.0f64);
            let mut rng = crate::numeric::SplitMix64::new(3);
            for _ in 0..300 {
                let d = DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, rng.next_f64() - 0.5).normalize();
                let on = facets.project(d, NONE);
                curved = curved.max((on.point - d).length());
                straight = straight.max((flat.project(d, NONE).point - d).length());
                // a point on a patch projects onto itself
                assert!((facets.project(on.point, on.face).point - on.point).length() < 1e-12);
            }
            assert!(
                curved < straight / 10.0,
                "{kind:?}: the patches are {curved} off the sphere, the flat triangles {straight}"
            );
        }
        // a tangled file: a folded element, so the flat triangles alone
        let s =
            crate::generate::perturb_surface(&surface(SurfaceShape::Sphere, SurfaceKind::Tri, 2, 4).unwrap(), 0.8, 1)
                .unwrap();
        let mesh = s.flat();
        let facets = Facets::new(s.points(), mesh.kinds(), |e| mesh.element(e), |_| 0, |_| 0);
        assert!(s.stats().inverted > 0 && facets.patch.iter().all(|p| p.is_none()));
    }

    #[test]
    fn analytic_projections_by_hand() {
        let s = Analytic::Sphere { centre: DVec3::new(1.0, 0.0, 0.0), radius: 2.0 };
        let q = s.project(DVec3::new(1.0, 0.0, 5.0), NONE);
        assert_eq!((q.point, q.normal), (DVec3::new(1.0, 0.0, 2.0), DVec3::Z));
        let t = Analytic::Torus { major: 3.0, minor: 1.0 };
        let q = t.project(DVec3::new(0.0, 5.0, 0.0), NONE);
        assert_eq!((q.point, q.normal), (DVec3::new(0.0, 4.0, 0.0), DVec3::Y));
        let c = Analytic::CappedCylinder { radius: 1.0, z0: 0.0, z1: 2.0 };
        assert_eq!(c.project(DVec3::new(3.0, 0.0, 1.0), NONE).point, DVec3::new(1.0, 0.0, 1.0));
        let top = c.project(DVec3::new(0.2, 0.0, 2.5), NONE);
        assert_eq!((top.point, top.normal, top.face), (DVec3::new(0.2, 0.0, 2.0), DVec3::Z, 2));
        // kept on its part: a side point pulled over the top stays on the side, at the rim
        let side = c.project(DVec3::new(0.9, 0.0, 2.5), 0);
        assert_eq!((side.point, side.normal), (DVec3::new(1.0, 0.0, 2.0), DVec3::X));
    }
}
