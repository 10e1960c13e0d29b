//! Planning a pass: the visit order (input or Chen's priority) and the untangling sweeps.

use crate::mesh::Mesh;
use crate::numeric::order::total_order_key;

use super::*;

impl Smoother<Star> {
    /// Plans the visit sequence of the next pass, returns it (also kept in
    /// [`schedule`](Self::schedule)).
    ///
    /// [`Order::Input`]: the free nodes in node order.
    ///
    /// [`Order::Priority`] — our reading of Chen et al. (2003) §4.2: the priority is computed
    /// once per pass from each free node's star quality (the smallest α/β of its elements).
    /// The range [worst, best] of these is split linearly into `B` =
    /// [`SmoothOptions::priority_bins`] (5) equal bins; the worst bin has the highest
    /// priority `B−1`, the best bin priority 0 (all nodes get priority 0 when every star is
    /// equally good). An inner loop lowers the current priority from `B−1` to 0 and smooths
    /// every node whose priority is at or above it ("if the current node's priority is less
    /// than that of the current priority, it will not be smoothed in the inner priority
    /// loop"). So the worst nodes are visited up to `B` times a pass, the best once; within
    /// one inner loop nodes go worst first (ties by node number).
    pub fn plan(&mut self, mesh: &Mesh) -> &[u32] {
        self.begin_plan(mesh);
        while !self.plan_some(mesh, usize::MAX) {}
        &self.schedule
    }

    /// Plans on from where [`begin_plan`](Self::begin_plan) or the last call left off,
    /// measuring at most `max_stars` more stars (at least one) for the priority order.
    /// Returns true when the schedule is complete.
    pub fn plan_some(&mut self, mesh: &Mesh, max_stars: usize) -> bool {
        self.plan_some_in(&mut ReadOnly(mesh), max_stars)
    }

    /// Plans the next untangling sweep of a pass whose visits so far `counts` holds (see
    /// `plan_untangle_sweep_in`). The one place that
    /// decides, for [`sweep`](Self::sweep) and for the page's sliced pass.
    pub fn plan_untangle_sweep(&mut self, mesh: &Mesh, counts: &mut SweepCounts) -> bool {
        self.plan_untangle_sweep_in(&mut ReadOnly(mesh), counts)
    }
}

impl<S: DriverStar> Smoother<S> {
    /// Starts planning the next pass in steps: [`plan_some`](Self::plan_some) until it
    /// returns true gives the same [`schedule`](Self::schedule) as [`plan`](Self::plan),
    /// for a caller that must stay responsive (the page: measuring every star of a
    /// 1M-node mesh for the priority order takes seconds).
    /// A pass begins here: the smoother takes the facts its visits need about the mesh
    /// (quadratic elements, curved edges) now.
    pub fn begin_plan(&mut self, mesh: &S::Mesh) {
        self.refresh_mesh_facts(mesh);
        self.bounds = std::sync::OnceLock::new();
        if self.grading_bound.is_none() {
            // the run's first pass: the grading as the run found the mesh (none if tangled)
            let keep = self.options.keep_grading;
            self.grading_bound = Some(keep.unwrap_or_else(|| mesh.valid_reading().map_or(f64::INFINITY, |r| r.grading)));
        }
        self.schedule.clear();
        self.sweep_moves_from = None;
        self.ranked.clear();
        self.plan_next = 0;
        if self.options.order == Order::Priority {
            self.quality.clear();
            self.quality.resize(mesh.node_count(), f64::NAN);
        }
    }

    /// [`plan_some`](Smoother::plan_some) over any [`StarView`].
    pub(crate) fn plan_some_in<V: StarView<Mesh = S::Mesh>>(&mut self, view: &mut V, max_stars: usize) -> bool {
        let done = self.plan_some_stars(view, max_stars);
        if done {
            self.note_tangled(view);
        }
        done
    }

    /// Notes whether the mesh has an inverted element now, for the untangling objectives
    /// ([`Objective::only_untangles`](crate::objective::Objective::only_untangles)), which
    /// leave a valid mesh where it is (Mesquite's untangler stops at once on a valid mesh);
    /// read only by the strategies that optimise.
    pub(crate) fn note_tangled<V: StarView<Mesh = S::Mesh>>(&mut self, view: &V) {
        self.tangled = !matches!(self.options.strategy, Strategy::Laplace | Strategy::Smart)
            && (0..view.mesh().element_count()).any(|e| view.is_inverted(e));
    }

    fn plan_some_stars<V: StarView<Mesh = S::Mesh>>(&mut self, view: &mut V, max_stars: usize) -> bool {
        let n = view.mesh().node_count();
        if self.plan_next >= n {
            return true;
        }
        match self.options.order {
            Order::Input => {
                let mesh = view.mesh();
                self.schedule.extend((0..n as u32).filter(|&i| mesh.is_free(i as usize)));
                self.plan_next = n;
                true
            }
            Order::Priority => {
                let mut measured = 0usize;
                while self.plan_next < n && measured < max_stars.max(1) {
                    let i = self.plan_next;
                    if view.mesh().is_free(i) {
                        let mesh = view.star_mesh(i);
                        self.quality[i] = match S::shape_from_mesh(mesh, i) {
                            Some(q) => q,
                            None => {
                                self.star.gather_for_measures(mesh, i);
                                self.star.min_shape_at(self.star.x0())
                            }
                        };
                        self.ranked.push(i as u32);
                        measured += 1;
                    }
                    self.plan_next += 1;
                }
                if self.plan_next < n {
                    return false;
                }
                self.schedule_by_priority();
                true
            }
        }
    }

    /// The priority schedule from the measured star qualities (see [`plan`](Self::plan)).
    fn schedule_by_priority(&mut self) {
        let quality = &self.quality;
        let q = |i: usize| tie_scale(quality[i]);
        // sorted as (key, node) pairs, not through a comparator that looks the qualities up
        // (random reads over the whole array); the key orders as `f64::total_cmp` does
        let mut keyed: Vec<(u64, u32)> = self.ranked.iter().map(|&i| (total_order_key(q(i as usize)), i)).collect();
        keyed.sort_unstable();
        self.ranked.clear();
        self.ranked.extend(keyed.iter().map(|&(_, i)| i));
        let bins = self.options.priority_bins;
        let (Some(&first), Some(&last)) = (self.ranked.first(), self.ranked.last()) else {
            return;
        };
        let (lo, hi) = (q(first as usize), q(last as usize));
        let range = hi - lo;
        let priority = |v: f64| -> u32 {
            if !(range > 0.0 && range.is_finite()) {
                return 0;
            }
            let bin = ((v - lo) / range * bins as f64).floor();
            let bin = if bin.is_nan() { 0 } else { (bin.max(0.0) as u32).min(bins - 1) };
            bins - 1 - bin
        };
        for level in (0..bins).rev() {
            for &i in &self.ranked {
                if priority(q(i as usize)) < level {
                    break; // ranked worst first: the rest have lower priority
                }
                self.schedule.push(i);
            }
        }
    }

    /// Plans the next untangling sweep of a pass whose visits so far `counts` holds (see
    /// [`SmoothOptions::untangle_sweeps`]): the free nodes of every inverted element and
    /// the free neighbours of its corners, worst star first (smallest α/β, ties by node
    /// number), into [`revisits`](Self::revisits), counted in `counts.untangle_sweeps`.
    /// Returns false — no sweep — when no element is inverted, the sweeps are at their
    /// limit, the last sweep moved no node, or the strategy never optimises.
    pub(crate) fn plan_untangle_sweep_in<V: StarView<Mesh = S::Mesh>>(
        &mut self,
        view: &mut V,
        counts: &mut SweepCounts,
    ) -> bool {
        self.revisits.clear();
        let stalled = self.sweep_moves_from.is_some_and(|m| counts.moves == m);
        if stalled
            || counts.untangle_sweeps >= self.options.untangle_sweeps
            || matches!(self.options.strategy, Strategy::Laplace | Strategy::Smart)
        {
            return false;
        }
        let mesh = view.mesh();
        self.marked.clear();
        self.marked.resize(mesh.node_count(), false);
        for e in 0..mesh.element_count() {
            if self.star.known_valid(mesh, e) || !view.is_inverted(e) {
                continue;
            }
            for &c in mesh.element_corners(e) {
                let c = c as usize;
                for m in std::iter::once(c).chain(mesh.neighbours(c).iter().map(|&m| m as usize)) {
                    if mesh.is_free(m) && !self.marked[m] {
                        self.marked[m] = true;
                        self.revisits.push(m as u32);
                    }
                }
            }
        }
        // by quality (as `f64::total_cmp` orders it), ties to the lower node: (key, node) pairs
        let mut ranked: Vec<(u64, u32)> = Vec::with_capacity(self.revisits.len());
        for &n in &self.revisits {
            self.marked[n as usize] = false;
            self.star.gather_for_measures(view.star_mesh(n as usize), n as usize);
            ranked.push((total_order_key(tie_scale(self.star.min_shape_at(self.star.x0()))), n));
        }
        ranked.sort_unstable();
        self.revisits.clear();
        self.revisits.extend(ranked.iter().map(|&(_, n)| n));
        if self.revisits.is_empty() {
            return false;
        }
        counts.untangle_sweeps += 1;
        self.sweep_moves_from = Some(counts.moves);
        true
    }

    /// The visit sequence of the last untangling sweep planned.
    pub fn revisits(&self) -> &[u32] {
        &self.revisits
    }
}

/// A star's quality as the priority order ranks it: rounded to a multiple of 2⁻⁴⁰
/// (about 10⁻¹²), so that stars equal but for the rounding of their coordinates — a
/// regular mesh's, or any mesh's scaled by 3 — tie, and the tie goes to the lower node
/// number. The shape measures are scale-free; their roundings are not, and ranked by the
/// last bits a mesh and its copy scaled by 3 were smoothed in different orders (issue
/// 29: a smallest dihedral angle of 13.30° or 15.98° after one pass).
pub(crate) fn tie_scale(q: f64) -> f64 {
    const STEP: f64 = (1u64 << 40) as f64;
    if q.is_finite() && q.abs() < 1e6 {
        (q * STEP).round() / STEP
    } else {
        q
    }
}
