//! The objectives of one free node of a volume mesh, over its star of corners (a
//! tetrahedron is one corner; a hexahedron, wedge or pyramid is its measured corners):
//! the planar objectives carried to solids, by the same command-line names
//! ([`ObjectiveKind`]), behind the same [`Objective`] trait, so the same solvers and
//! drivers run them ([`solid_objective`]). This is the 3D registry: [`solid_form`] gives a
//! kind's form on solids, `None` for a kind that is planar only (the command line and
//! the page then refuse it on a volume, [`solid_objective`]'s message).
//!
//! | kind | goal | terms, per corner tetrahedron of the star |
//! |---|---|---|
//! | `old` | max-min | the mean ratio `q` (the 3D shape measure Chen's α generalises) |
//! | `sine` | max-min | the signed sine of each of the six dihedral angles — Freitag 1997 |
//! | `new` | sum | `(1 − q_δ)² + k1·η_δ²`, the mean ratio with Escobar et al.'s regularised determinant — Chen's form carried to solids |
//! | `condition` | sum | κ², Knupp's condition number against the corner's reference W (the equilateral tetrahedron) |
//! | `condition-max` | max-min | −κ |
//! | `untangle` | sum | Knupp's `(|6V − β| − (6V − β))²`, with the planar shift β |
//! | `untangle-mindet` | max-min | 6V, the Jacobian determinant |
//!
//! Every term is a function of the tetrahedron's four corners with the free node first
//! (the star keeps each tetrahedron in an even permutation of its corners, so its volume
//! keeps its sign: [`crate::quality::tet::with_first`]), and its gradient is analytic. The
//! measures that weigh a corner by its ideal shape take the star's reference
//! ([`CornerStar::reference`]: the mesh's element kind's W, computed once per kind).
//! The formulas, in one notation: `docs/formulas.md` §8.
//!
//! `star.rs` holds the star ([`CornerStar`]). `known_solids.rs` and `memo.rs`
//! hold what it keeps between questions. `objectives.rs` holds the objectives
//! ([`SolidObjective`]).

use super::{Objective, ObjectiveKind};
use crate::error::{Error, Result};

mod known_solids;
mod objectives;
mod star;
#[cfg(test)]
mod tests;
mod memo;
pub(crate) use memo::framed;

pub use objectives::{RegularisedMeanRatio, SolidObjective};
pub use star::{CornerStar, StarCorner, StarSolid};

/// The 3D registry: the form of objective `kind` on tetrahedral meshes, with its default
/// parameters, or `None` when `kind` is planar only (a kind added to [`ObjectiveKind`]
/// gets its arm here, `None` until it has a tetrahedral form).
pub fn solid_form(kind: ObjectiveKind) -> Option<SolidObjective> {
    Some(match kind {
        ObjectiveKind::MaxMinShape => SolidObjective::MeanRatio,
        ObjectiveKind::Sine => SolidObjective::DihedralSine,
        ObjectiveKind::SmoothShape => SolidObjective::Regularised(RegularisedMeanRatio::default()),
        ObjectiveKind::Condition => SolidObjective::Condition,
        ObjectiveKind::ConditionMax => SolidObjective::ConditionMax,
        ObjectiveKind::Untangle => SolidObjective::Untangle { beta: super::UNTANGLE_BETA },
        ObjectiveKind::UntangleMinDet => SolidObjective::MinDet,
    })
}

/// The objective kinds that have a form on tetrahedra ([`solid_form`]), in
/// [`ObjectiveKind::ALL`]'s order: the choices on a volume.
pub fn solid_kinds() -> impl Iterator<Item = ObjectiveKind> {
    ObjectiveKind::ALL.into_iter().filter(|&k| solid_form(k).is_some())
}

/// The objective of `kind` for tetrahedral meshes ([`solid_form`]), boxed for the drivers;
/// refused, naming the kinds that have a tetrahedral form, when `kind` is planar only.
pub fn solid_objective(kind: ObjectiveKind) -> Result<Box<dyn Objective<CornerStar> + Send + Sync>> {
    match solid_form(kind) {
        Some(o) => Ok(Box::new(o)),
        None => Err(Error::Invalid(format!(
            "the objective {kind} is planar only: on tetrahedra choose {}",
            solid_kinds().map(|k| k.name()).collect::<Vec<_>>().join(", ")
        ))),
    }
}

/// What the objective of `kind` is on tetrahedra, in a few words for people (the page's
/// headings of a tetrahedral mesh; the planar words are [`ObjectiveKind::describe`]);
/// `None` when `kind` is planar only.
pub fn describe_solid(kind: ObjectiveKind) -> Option<&'static str> {
    solid_form(kind).map(|o| o.describe())
}
