//! What `smoothlab stats` reads of a set of elements: the extremes a user reads.

use glam::{DVec2, DVec3};

use super::{measure_element, solid};
use crate::mesh::{ElementKind, Mesh, VolumeKind};

/// The extremes the statistics print of a set of elements: the smallest and largest angle
/// (a planar element's corner angles, a volume element's dihedral angles), the smallest
/// corner scaled Jacobian and the smallest quality (α/β in 2D, the mean ratio in volumes).
///
/// The drivers keep a valid mesh within its own reading: a move on a valid star is kept
/// only if the star reads within what the mesh read at the start of the pass
/// ([`within`](Self::within); `docs/formulas.md` §4), whatever the objective's own
/// measure says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reading {
    /// Degrees.
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    pub min_scaled_jacobian: f64,
    /// +∞ where not taken; as a bound, −∞ where not compared.
    pub min_quality: f64,
    /// The mesh's grading ([`super::grading`]): a property of pairs of elements, not of
    /// one, so [`within`](Self::within) does not compare it; the drivers check a moved
    /// star's pairs against it. −∞ for an element or no pair; as a bound, +∞ where none.
    pub grading: f64,
}

impl Default for Reading {
    /// The reading of no element.
    fn default() -> Self {
        Reading {
            min_angle_deg: f64::INFINITY,
            max_angle_deg: f64::NEG_INFINITY,
            min_scaled_jacobian: f64::INFINITY,
            min_quality: f64::INFINITY,
            grading: f64::NEG_INFINITY,
        }
    }
}

impl Reading {
    /// A planar element (or a surface element in its own plane) with nodes `p`, as the
    /// statistics read it ([`super::element_quality`]), and whether it is inverted. The
    /// planar statistics print no scaled Jacobian (a corner's is the sine of its angle,
    /// which the angles bound), so it reads −∞.
    pub fn planar(kind: ElementKind, p: &[DVec2]) -> (Self, bool) {
        let q = measure_element::<true, false, false>(kind, &p[..kind.node_count()], |_, _, _| {});
        let r = Reading {
            min_angle_deg: q.min_angle.to_degrees(),
            max_angle_deg: q.max_angle.to_degrees(),
            min_scaled_jacobian: f64::NEG_INFINITY,
            min_quality: q.shape,
            grading: f64::NEG_INFINITY,
        };
        (r, q.inverted)
    }

    /// Whether a planar element reads within `bounds`: [`planar`](Self::planar)'s answer,
    /// bit for bit. A linear triangle's angles are compared by their cosines, and measured
    /// only within 10⁻⁹ of a bound's cosine (as for a volume's dihedral angles), where
    /// the bounds leave the quality out.
    pub fn planar_within(kind: ElementKind, p: &[DVec2], bounds: &Reading) -> bool {
        if kind == ElementKind::Tri3 && bounds.min_quality == f64::NEG_INFINITY {
            let (cos_lo, cos_hi) = (bounds.min_angle_deg.to_radians().cos(), bounds.max_angle_deg.to_radians().cos());
            let clear = (0..3).all(|i| {
                let (a, b) = (p[(i + 1) % 3] - p[i], p[(i + 2) % 3] - p[i]);
                let c = a.dot(b) / (a.length() * b.length());
                a.perp_dot(b) > 0.0 && c < cos_lo - 1e-9 && c > cos_hi + 1e-9
            });
            if clear {
                return true;
            }
        }
        Reading::planar(kind, p).0.within(bounds)
    }

    /// The reading of a planar `mesh` (or a surface's), element `e` with nodes `points(e)`;
    /// `None` where an element is inverted.
    pub fn planar_mesh(mesh: &Mesh, points: impl Fn(usize) -> [DVec2; 9]) -> Option<Self> {
        let mut sizes = Vec::with_capacity(mesh.element_count());
        let r = (0..mesh.element_count()).try_fold(Reading::default(), |r, e| {
            let p = points(e);
            let (q, inverted) = Reading::planar(mesh.kind(e), &p);
            sizes.push(super::grading::planar_size(mesh.kind(e), &p[..mesh.kind(e).node_count()]));
            (!inverted).then(|| r.and(q))
        })?;
        Some(r.with_grading(super::grading::largest_ratio(&sizes, super::grading::edge_neighbours(mesh))))
    }

    /// This reading as a bound with the mesh's grading (+∞ where no pair has one).
    pub fn with_grading(self, grading: Option<f64>) -> Self {
        Reading { grading: grading.unwrap_or(f64::INFINITY), ..self }
    }

    /// A volume element of `kind` with nodes `p` (all of them), as the statistics read it
    /// ([`solid::solid_reading`]).
    pub fn solid(kind: VolumeKind, p: &[DVec3]) -> Self {
        solid::solid_reading(kind, p, true)
    }

    /// This reading and another's together. A measure that is not a number is the worst
    /// there is.
    pub fn and(self, other: Reading) -> Self {
        let least = |a: f64, b: f64| if a.is_nan() || b.is_nan() { f64::NEG_INFINITY } else { a.min(b) };
        let most = |a: f64, b: f64| if a.is_nan() || b.is_nan() { f64::INFINITY } else { a.max(b) };
        Reading {
            min_angle_deg: least(self.min_angle_deg, other.min_angle_deg),
            max_angle_deg: most(self.max_angle_deg, other.max_angle_deg),
            min_scaled_jacobian: least(self.min_scaled_jacobian, other.min_scaled_jacobian),
            min_quality: least(self.min_quality, other.min_quality),
            grading: most(self.grading, other.grading),
        }
    }

    /// These bounds without the quality's (where the caller's own rule keeps it).
    pub fn without_quality(self) -> Self {
        Reading { min_quality: f64::NEG_INFINITY, ..self }
    }

    /// Whether this reading lies within `bounds`: its smallest angle, scaled Jacobian and
    /// quality not lower, its largest angle not higher.
    pub fn within(&self, bounds: &Reading) -> bool {
        self.min_angle_deg >= bounds.min_angle_deg
            && self.max_angle_deg <= bounds.max_angle_deg
            && self.min_scaled_jacobian >= bounds.min_scaled_jacobian
            && self.min_quality >= bounds.min_quality
    }

    /// Whether the dihedral angle of cosine `c` (clamped, as
    /// [`super::tet::dihedral_cosines`]) is within the bounds, as its angle in degrees
    /// compares; `cos_lo`, `cos_hi` the bounds' cosines. The inverse cosine is taken only
    /// within 10⁻⁹ of a bound's cosine, far beyond the few ulps by which the two comparisons
    /// could differ (the inverse cosine's slope is at least 1).
    #[inline]
    pub(crate) fn angle_within(&self, c: f64, cos_lo: f64, cos_hi: f64) -> bool {
        if c < cos_lo - 1e-9 && c > cos_hi + 1e-9 {
            return true;
        }
        let a = c.acos().to_degrees();
        a >= self.min_angle_deg && a <= self.max_angle_deg
    }
}
