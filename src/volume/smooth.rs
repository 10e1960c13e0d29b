//! Smoothing a tetrahedral mesh: the planar drivers ([`crate::smooth`]) over a star of
//! tetrahedra. Nothing here decides where a node goes: the tetrahedral mesh and its star
//! implement the drivers' two traits ([`SmoothMesh`], [`DriverStar`]) and the
//! [`Smoother`] does the rest, strategy by strategy, as for planar meshes.
//!
//! The measures the drivers take of a tetrahedral star, in the planar measures' roles:
//! - the shape ([`Measure::Shape`]: the smart Laplacian, the priority order, Chen's rule
//!   2) is the mean ratio of each tetrahedron (1 for the regular one);
//! - the sine ([`Measure::MinSine`], the thresholds of Freitag's C1/C2/C3) is the
//!   smallest sine of the dihedral angles (Freitag 1997 in 3D);
//! - a tetrahedron is inverted when its signed volume is ≤ 0; the inversion the
//!   validity guard compares is `Σ max(0, −6V)` over the star.
//!
//! Quadratic (10-node) tetrahedra are measured by their corners; their mid-edge nodes
//! follow the corners to the edges' middles.

use glam::DVec3;

use super::{VolumeMesh, VolumeKind};
use crate::error::Result;
use crate::objective::{Objective, StarCorner, CornerStar};
use crate::quality::tet as q3;
use crate::smooth::{
    DriverStar, ElementScore, Verdict, Measure, PassRecord, SmoothMesh, SmoothOptions, Smoother, StarQuality, StarView, SweepCounts,
};

impl SmoothMesh for VolumeMesh {
    type Point = DVec3;
    #[inline]
    fn node_count(&self) -> usize {
        VolumeMesh::node_count(self)
    }
    #[inline]
    fn is_free(&self, n: usize) -> bool {
        VolumeMesh::is_free(self, n)
    }
    #[inline]
    fn position(&self, n: usize) -> DVec3 {
        self.nodes()[n]
    }
    #[inline]
    fn neighbours(&self, n: usize) -> &[u32] {
        VolumeMesh::neighbours(self, n)
    }
    #[inline]
    fn element_count(&self) -> usize {
        VolumeMesh::element_count(self)
    }
    #[inline]
    fn element_corners(&self, e: usize) -> &[u32] {
        &self.element(e)[..4]
    }
    #[inline]
    fn has_quadratic(&self) -> bool {
        self.is_quadratic()
    }
}

impl DriverStar for CornerStar {
    type Mesh = VolumeMesh;
    /// The node's corner of each element: the node first, then its three edge neighbours
    /// in the kind's order ([`VolumeKindRow::corner_edges`](crate::mesh::VolumeKindRow)),
    /// an even permutation of a tetrahedron's corners, so the volume keeps its sign.
    fn gather(&mut self, mesh: &VolumeMesh, node: usize) {
        self.node = node as u32;
        self.x0 = mesh.nodes()[node];
        self.kind = mesh.kind();
        self.tets.clear();
        let row = mesh.kind().row();
        for &e in mesh.node_tets(node) {
            let ids = &mesh.element(e as usize)[..row.corners];
            let Some(slot) = ids.iter().position(|&i| i as usize == node) else { continue };
            let [a, b, c] = row.corner_edges[slot];
            let pts = [slot, a, b, c].map(|k| mesh.nodes()[ids[k] as usize]);
            self.tets.push(StarCorner { element: e, pts });
        }
    }
    #[inline]
    fn x0(&self) -> DVec3 {
        self.x0
    }
    fn restar(&mut self, x: DVec3) {
        self.x0 = x;
        for t in &mut self.tets {
            t.pts[0] = x;
        }
    }
    fn shape_at(&self, x: DVec3) -> (f64, u32) {
        let (mut min, mut inverted) = (f64::INFINITY, 0);
        for t in &self.tets {
            let p = t.at(x);
            min = min.min(q3::mean_ratio(&p, self.reference()));
            inverted += q3::is_inverted(&p) as u32;
        }
        (min, inverted)
    }
    fn quality(&self, x: Option<DVec3>) -> StarQuality {
        let mut q = StarQuality::BEST;
        for t in &self.tets {
            let p = x.map_or(t.pts, |x| t.at(x));
            q.min_shape = q.min_shape.min(q3::mean_ratio(&p, self.reference()));
            q.min_sine = q.min_sine.min(q3::dihedral_sines(&p).into_iter().fold(f64::INFINITY, f64::min));
            q.inverted += q3::is_inverted(&p) as u32;
        }
        q
    }
    fn smart_accepts(&self, c: DVec3, m: Measure) -> bool {
        let measure = |p: &[DVec3; 4]| match m {
            Measure::Shape => q3::mean_ratio(p, self.reference()),
            Measure::MinSine => q3::dihedral_sines(p).into_iter().fold(f64::INFINITY, f64::min),
        };
        let (mut before, mut after) = (f64::INFINITY, f64::INFINITY);
        for t in &self.tets {
            let p1 = t.at(c);
            if !q3::is_inverted(&t.pts) && q3::is_inverted(&p1) {
                return false;
            }
            before = before.min(measure(&t.pts));
            after = after.min(measure(&p1));
        }
        after > before
    }
    fn inverted_now(&self) -> usize {
        self.tets.iter().filter(|t| q3::is_inverted(&t.pts)).count()
    }
    fn inverted_at(&self, x: DVec3) -> usize {
        self.tets.iter().filter(|t| q3::is_inverted(&t.at(x))).count()
    }
    fn inversion(&self, x: DVec3) -> f64 {
        self.tets.iter().map(|t| (-6.0 * q3::signed_volume(&t.at(x))).max(0.0)).sum()
    }
    fn verdict(&self, x: DVec3, m: Measure) -> Verdict {
        let mut v = Verdict::default();
        for t in &self.tets {
            v.add(&ElementScore::tet(&t.pts, self.reference(), m), &ElementScore::tet(&t.at(x), self.reference(), m));
        }
        v
    }
    /// A 10-node mesh's tetrahedra with their mid-edge nodes (those of the node's edges
    /// following it to their middles, as [`VolumeMesh::follow_mid_nodes`] moves them), so the
    /// rule reads what the statistics read.
    fn verdict_in(&self, mesh: &VolumeMesh, x: DVec3, m: Measure) -> Verdict {
        match mesh.kind() {
            VolumeKind::Tet4 => return self.verdict(x, m),
            VolumeKind::Tet10 => {}
        }
        let row = mesh.kind().row();
        let n = self.node;
        let mut v = Verdict::default();
        for t in &self.tets {
            let ids = mesh.element(t.element as usize);
            let before: [DVec3; 10] = std::array::from_fn(|j| mesh.nodes()[ids[j] as usize]);
            let mut after = before;
            for (j, &i) in ids[..row.corners].iter().enumerate() {
                if i == n {
                    after[j] = x;
                }
            }
            for (k, &[a, b]) in row.edges.iter().enumerate() {
                let mid = row.corners + k;
                if (ids[a] == n || ids[b] == n) && !mesh.fixed()[ids[mid] as usize] {
                    after[mid] = 0.5 * (after[a] + after[b]);
                }
            }
            let r = self.reference();
            v.add(&ElementScore::tet10(&before, r, m), &ElementScore::tet10(&after, r, m));
        }
        v
    }
}

/// A tetrahedral mesh as its own [`StarView`].
pub(crate) struct Solid<'a>(pub &'a mut VolumeMesh);

impl StarView for Solid<'_> {
    type Mesh = VolumeMesh;
    #[inline]
    fn mesh(&self) -> &VolumeMesh {
        self.0
    }
    #[inline]
    fn star_mesh(&mut self, _: usize) -> &VolumeMesh {
        self.0
    }
    fn place(&mut self, n: usize, x: DVec3) {
        self.0.nodes_mut()[n] = x;
        if self.0.is_quadratic() {
            self.0.follow_mid_nodes(n);
        }
    }
    fn is_inverted(&self, e: usize) -> bool {
        q3::is_inverted(&self.0.corners(e))
    }
}

/// A smoother of tetrahedral meshes: the planar drivers' [`Smoother`] over tetrahedral
/// stars, with the same options, pass by pass.
#[derive(Clone, Debug)]
pub struct VolumeSmoother {
    smoother: Smoother<CornerStar>,
}

impl VolumeSmoother {
    /// A smoother with checked options.
    pub fn new(options: SmoothOptions) -> Result<Self> {
        Ok(VolumeSmoother { smoother: Smoother::new(options)? })
    }
    pub fn options(&self) -> &SmoothOptions {
        self.smoother.options()
    }
    /// The node loop of a pass (the planned order, then the untangling sweeps).
    pub fn sweep(&mut self, mesh: &mut VolumeMesh, objective: &dyn Objective<CornerStar>) -> SweepCounts {
        self.smoother.sweep_in(&mut Solid(mesh), objective)
    }
    /// One pass with its record: counts and time, and the mesh's statistics after it
    /// ([`super::volume_stats`]: the angles are dihedral angles, the quality the mean
    /// ratio). `clock` returns milliseconds.
    pub fn pass(
        &mut self,
        mesh: &mut VolumeMesh,
        objective: &dyn Objective<CornerStar>,
        pass: u32,
        clock: &dyn Fn() -> f64,
    ) -> PassRecord {
        let t0 = clock();
        let counts = self.sweep(mesh, objective);
        let elapsed_ms = clock() - t0;
        let t1 = clock();
        let after = super::volume_stats(mesh).quick();
        let objective_total = Some(self.smoother.objective_total_in(&mut Solid(mesh), objective));
        PassRecord { pass, counts, after, objective_total, elapsed_ms, stats_ms: clock() - t1 }
    }
}

/// Runs `passes` passes of a new [`VolumeSmoother`] over `mesh`, returning their records.
pub fn smooth_volume(
    mesh: &mut VolumeMesh,
    objective: &dyn Objective<CornerStar>,
    options: SmoothOptions,
    passes: u32,
    clock: &dyn Fn() -> f64,
) -> Result<Vec<PassRecord>> {
    let mut s = VolumeSmoother::new(options)?;
    Ok((1..=passes).map(|p| s.pass(mesh, objective, p, clock)).collect())
}
