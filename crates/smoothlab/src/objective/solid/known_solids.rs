//! What a star keeps of its elements other than tetrahedra.
//! Each element keeps its measures at the last two positions asked.
//! The stars keep each element's last measures from visit to visit.

use glam::DVec3;

use super::StarSolid;
use crate::mesh::VolumeKind;
use crate::quality::solid::{CornerShapes, Validity};

/// A measure of a star's element kept for the last two positions of the free node asked:
/// the drivers ask the same two (as gathered, and the move's) in the smart Laplacian's test
/// and again in the acceptance rule.
#[derive(Clone, Debug, PartialEq)]
pub struct PositionMemo<T: Copy>([std::cell::Cell<Option<(DVec3, T)>>; 2]);

impl<T: Copy> Default for PositionMemo<T> {
    fn default() -> Self {
        PositionMemo([std::cell::Cell::new(None), std::cell::Cell::new(None)])
    }
}

impl<T: Copy> PositionMemo<T> {
    /// The value kept for `x`, else `measure()`, kept (in the first place while it is
    /// empty, then in the second).
    #[inline]
    pub fn get_or(&self, x: DVec3, measure: impl FnOnce() -> T) -> T {
        for m in &self.0 {
            if let Some((at, v)) = m.get() {
                if at == x {
                    return v;
                }
            }
        }
        let v = measure();
        let slot = if self.0[0].get().is_none() { 0 } else { 1 };
        self.0[slot].set(Some((x, v)));
        v
    }
    /// The value kept for `x`, if any.
    #[inline]
    pub fn kept(&self, x: DVec3) -> Option<T> {
        self.0.iter().find_map(|m| m.get().filter(|&(at, _)| at == x).map(|(_, v)| v))
    }
    /// Keeps `v` for `x` in the first place (a memo just made, before any question).
    #[inline]
    fn start_with(&self, x: DVec3, v: T) {
        self.0[0].set(Some((x, v)));
    }
}

/// The validity and shape (with the shape's terms, [`CornerShapes`], and the least corner
/// determinant the acceptance rule screens the size with) of the stars' elements
/// other than tetrahedra, kept from visit to visit: each as the element's last star left
/// it, with the corners it was measured at.
/// A star gathered later starts its element's [`PositionMemo`]s with them where the corners
/// are still those, bit for bit (a neighbour's visit that moved nothing of the element, or
/// the visit that moved it: its measures at the new position), so an element is not
/// measured again at a position it was measured at. Both measures are functions of the
/// kind and the corners alone, so an answer kept is the answer measuring would give.
///
/// Direct-mapped by element number, at most [`KnownSolids::MAX_SLOTS`] slots of 376 bytes
/// (some 25 MB of a mesh of many elements other than tetrahedra), none for a mesh of
/// tetrahedra. A copy starts empty: it is a cache.
#[derive(Default)]
pub(crate) struct KnownSolids {
    slots: Vec<KnownSolid>,
}

// the slot's size that `KnownSolids` states
const _: () = assert!(std::mem::size_of::<KnownSolid>() == 376);

#[derive(Clone, Copy)]
struct KnownSolid {
    element: u32,
    kind: VolumeKind,
    corners: [DVec3; 8],
    validity: Option<Validity>,
    shape: Option<f64>,
    /// The shape's terms, where `has_terms` (a flag beside them rather than an `Option`, so
    /// that they are copied in place: [`CornerShapes::copy_from`]).
    has_terms: bool,
    terms: CornerShapes,
    least_det: Option<Option<(f64, f64)>>,
}

impl KnownSolid {
    const EMPTY: KnownSolid = KnownSolid {
        element: u32::MAX,
        kind: VolumeKind::Tet4,
        corners: [DVec3::ZERO; 8],
        validity: None,
        shape: None,
        has_terms: false,
        terms: CornerShapes::NONE,
        least_det: None,
    };
    /// Whether this slot holds `element` of `kind` at `corners`, bit for bit.
    fn holds(&self, element: u32, kind: VolumeKind, corners: &[DVec3]) -> bool {
        self.element == element && self.kind == kind && self.corners.iter().zip(corners).all(|(a, b)| same_bits(a, b))
    }
    /// [`holds`](Self::holds) of `e` with its free node at `x` (its corners compared where
    /// they are, not copied).
    fn holds_moved(&self, e: &StarSolid, x: DVec3) -> bool {
        let slot = e.slot as usize;
        self.element == e.element
            && self.kind == e.kind
            && self.corners.iter().zip(e.corners(&e.pts)).enumerate().all(|(j, (a, b))| same_bits(a, if j == slot { &x } else { b }))
    }
}

/// Whether `a` and `b` are the same bits.
#[inline]
fn same_bits(a: &DVec3, b: &DVec3) -> bool {
    let bits = |p: &DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    bits(a) == bits(b)
}

impl Clone for KnownSolids {
    fn clone(&self) -> Self {
        KnownSolids::default()
    }
}

impl std::fmt::Debug for KnownSolids {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "KnownSolids({} slots)", self.slots.len())
    }
}

impl KnownSolids {
    /// The most slots kept.
    pub const MAX_SLOTS: usize = 1 << 16;

    /// The slot of `element` (direct-mapped: its number modulo the power of two of slots).
    #[inline]
    fn slot(&self, element: u32) -> usize {
        element as usize & self.slots.len().wrapping_sub(1)
    }

    /// Starts `e`'s memos with what is known of it at its corners now.
    pub(super) fn recall(&self, e: &StarSolid) {
        let Some(k) = self.slots.get(self.slot(e.element)) else { return };
        if k.holds(e.element, e.kind, e.corners(&e.pts)) {
            let x = e.x();
            if let Some(v) = k.validity {
                e.measured.start_with(x, v);
            }
            if let Some(q) = k.shape {
                e.shaped.start_with(x, q);
            }
            let mut terms = e.terms.borrow_mut();
            terms.0 = k.has_terms.then_some(x);
            if k.has_terms {
                terms.1.copy_from(&k.terms);
            }
            if let Some(d) = k.least_det {
                e.least_det.start_with(x, d);
            }
        }
    }

    /// Whether `element` of `kind` was measured valid at `corners`, bit for bit.
    pub(super) fn valid_at(&self, element: u32, kind: VolumeKind, corners: &[DVec3]) -> bool {
        self.slots.get(self.slot(element)).is_some_and(|k| k.validity == Some(Validity::Valid) && k.holds(element, kind, corners))
    }

    /// Keeps what `e`'s memos know of it with its free node at `x`, in a mesh of
    /// `elements` elements.
    pub(super) fn keep(&mut self, e: &StarSolid, x: DVec3, elements: usize) {
        let (validity, shape) = (e.measured.kept(x), e.shaped.kept(x));
        let terms = e.terms.borrow();
        let terms = (terms.0 == Some(x)).then_some(&terms.1);
        let least_det = e.least_det.kept(x);
        if validity.is_none() && shape.is_none() {
            return;
        }
        let want = elements.next_power_of_two().min(Self::MAX_SLOTS);
        if self.slots.len() < want {
            // the slots move with the length: start again (once a mesh)
            self.slots.clear();
            self.slots.resize(want, KnownSolid::EMPTY);
        }
        let i = self.slot(e.element);
        let k = &mut self.slots[i];
        if k.holds_moved(e, x) {
            k.validity = validity.or(k.validity);
            k.shape = shape.or(k.shape);
            if let Some(t) = terms {
                k.has_terms = true;
                k.terms.copy_from(t);
            }
            k.least_det = least_det.or(k.least_det);
        } else {
            // field by field in place (a whole slot put together first is one more copy);
            // the corners past the kind's are not read
            (k.element, k.kind) = (e.element, e.kind);
            k.corners = e.pts;
            k.corners[e.slot as usize] = x;
            (k.validity, k.shape, k.has_terms, k.least_det) = (validity, shape, terms.is_some(), least_det);
            if let Some(t) = terms {
                k.terms.copy_from(t);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objective::CornerStar;
    use crate::quality::solid::validity;

    /// A star's elements other than tetrahedra start with what an earlier star measured of
    /// them ([`KnownSolids`]) exactly where their corners are still those: a neighbour's
    /// star recalls the shared hexahedra, the same numbers as measuring; after a corner
    /// moved, nothing is recalled.
    #[test]
    fn known_solids_are_recalled_only_at_the_corners_measured() {
        use crate::quality::solid::solid_shape;
        use crate::smooth::DriverStar;
        let block = crate::generate::hex_grid(&crate::generate::HexBlock::cube(3)).unwrap();
        let mut mesh = crate::generate::perturb_volume(&block, 0.2, 5).unwrap();
        let free: Vec<usize> = (0..mesh.node_count()).filter(|&n| mesh.is_free(n)).collect();
        let (n, m) = (free[0], *mesh.neighbours(free[0]).iter().find(|&&m| mesh.is_free(m as usize)).unwrap() as usize);
        let exact = |e: &StarSolid| (validity(e.kind, e.corners(&e.pts)), solid_shape(e.kind, e.corners(&e.pts)));
        let mut star = CornerStar::default();
        star.gather_for_measures(&mesh, n);
        let measured: Vec<u32> = star.elements.iter().map(|e| e.element).collect();
        for e in &star.elements {
            assert_eq!(e.shaped.kept(e.x()), None, "a first star knows nothing");
            e.validity_measured(e.x());
            e.shape_measured(e.x());
        }
        // the neighbour's star: the shared elements recalled, the others measured afresh
        star.gather_for_measures(&mesh, m);
        let mut recalled = 0;
        for e in &star.elements {
            let known = (e.measured.kept(e.x()), e.shaped.kept(e.x()));
            if measured.contains(&e.element) {
                let (v, q) = exact(e);
                assert_eq!(known, (Some(v), Some(q)), "element {}", e.element);
                recalled += 1;
            } else {
                assert_eq!(known, (None, None), "element {}", e.element);
            }
        }
        assert!(recalled >= 2, "{recalled}");
        // node n moves (a little): none of its elements is recalled
        let x = mesh.nodes()[n];
        mesh.nodes_mut()[n] = DVec3::new(x.x + 1e-9, x.y, x.z);
        star.gather_for_measures(&mesh, n);
        assert!(star.elements.iter().all(|e| e.measured.kept(e.x()).is_none() && e.shaped.kept(e.x()).is_none()));
    }

    /// What the stars keep of their elements from visit to visit answers as measuring does:
    /// after visits that measure each star where its node is and where it moves, as the
    /// acceptance rule does, an element known valid at its corners now is valid by the exact
    /// test (the untangling sweeps' planning reads it, `DriverStar::known_valid`), one
    /// measured folded is not known valid, and the least corner determinant a star recalls
    /// is the one taken now.
    #[test]
    fn what_is_known_after_visits_is_what_measuring_gives() {
        use crate::quality::solid::least_corner_det;
        use crate::smooth::DriverStar;
        let block = crate::generate::hex_grid(&crate::generate::HexBlock::cube(4)).unwrap();
        // moved by 0.9 mean edge lengths: some hexahedra folded
        let mut mesh = crate::generate::perturb_volume(&block, 0.9, 2).unwrap();
        let mut star = CornerStar::default();
        let free: Vec<usize> = (0..mesh.node_count()).filter(|&n| mesh.is_free(n)).collect();
        for (i, &n) in free.iter().enumerate() {
            star.gather_for_measures(&mesh, n);
            let x = star.x0() + DVec3::new(1e-3, -2e-3, 1.5e-3) * (i % 3) as f64;
            for e in &star.elements {
                for at in [e.x(), x] {
                    e.validity_measured(at);
                    e.least_corner_det_measured(at);
                }
            }
            mesh.nodes_mut()[n] = x;
        }
        // the last star's elements are kept at the next gather
        star.gather_for_measures(&mesh, free[0]);
        let (mut known, mut folded) = (0, 0);
        for e in 0..mesh.element_count() {
            let inverted = mesh.is_inverted(e);
            folded += inverted as usize;
            if star.known_valid(&mesh, e) {
                assert!(!inverted, "element {e} known valid");
                known += 1;
            }
        }
        assert!(known > mesh.element_count() / 2 && folded > 0, "{known} known valid, {folded} folded");
        let mut recalled = 0;
        for &n in &free {
            star.gather_for_measures(&mesh, n);
            for e in &star.elements {
                if let Some(d) = e.least_det.kept(e.x()) {
                    assert_eq!(d, least_corner_det(e.kind, e.corners(&e.pts)), "element {}", e.element);
                    recalled += 1;
                }
            }
        }
        assert!(recalled > 0);
    }
}
