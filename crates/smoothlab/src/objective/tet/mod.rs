//! The objectives of one free node of a tetrahedral mesh, over its star of tetrahedra:
//! the planar objectives carried to solids, by the same command-line names
//! ([`ObjectiveKind`]), behind the same [`Objective`] trait, so the same solvers and
//! drivers run them ([`tet_objective`]). This is the 3D registry: [`tet_form`] gives a
//! kind's form on tetrahedra, `None` for a kind that is planar only (the command line and
//! the page then refuse it on a volume, [`tet_objective`]'s message).
//!
//! | kind | goal | terms, per tetrahedron of the star |
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
//! `star.rs` holds the star ([`CornerStar`]). `known_solids.rs` and `tet_measures.rs`
//! hold what it keeps between questions. `objectives.rs` holds the objectives
//! ([`TetObjective`]).

use super::{Objective, ObjectiveKind};
use crate::error::{Error, Result};

mod known_solids;
mod objectives;
mod star;
#[cfg(test)]
mod tests;
mod tet_measures;
pub(crate) use tet_measures::framed;

pub use objectives::{RegularisedMeanRatio, TetObjective};
pub use star::{CornerStar, StarCorner, StarSolid};

/// The 3D registry: the form of objective `kind` on tetrahedral meshes, with its default
/// parameters, or `None` when `kind` is planar only (a kind added to [`ObjectiveKind`]
/// gets its arm here, `None` until it has a tetrahedral form).
pub fn tet_form(kind: ObjectiveKind) -> Option<TetObjective> {
    Some(match kind {
        ObjectiveKind::MaxMinShape => TetObjective::MeanRatio,
        ObjectiveKind::Sine => TetObjective::DihedralSine,
        ObjectiveKind::SmoothShape => TetObjective::Regularised(RegularisedMeanRatio::default()),
        ObjectiveKind::Condition => TetObjective::Condition,
        ObjectiveKind::ConditionMax => TetObjective::ConditionMax,
        ObjectiveKind::Untangle => TetObjective::Untangle { beta: super::UNTANGLE_BETA },
        ObjectiveKind::UntangleMinDet => TetObjective::MinDet,
    })
}

/// The objective kinds that have a form on tetrahedra ([`tet_form`]), in
/// [`ObjectiveKind::ALL`]'s order: the choices on a volume.
pub fn tet_kinds() -> impl Iterator<Item = ObjectiveKind> {
    ObjectiveKind::ALL.into_iter().filter(|&k| tet_form(k).is_some())
}

/// The objective of `kind` for tetrahedral meshes ([`tet_form`]), boxed for the drivers;
/// refused, naming the kinds that have a tetrahedral form, when `kind` is planar only.
pub fn tet_objective(kind: ObjectiveKind) -> Result<Box<dyn Objective<CornerStar> + Send + Sync>> {
    match tet_form(kind) {
        Some(o) => Ok(Box::new(o)),
        None => Err(Error::Invalid(format!(
            "the objective {kind} is planar only: on tetrahedra choose {}",
            tet_kinds().map(|k| k.name()).collect::<Vec<_>>().join(", ")
        ))),
    }
}

/// What the objective of `kind` is on tetrahedra, in a few words for people (the page's
/// headings of a tetrahedral mesh; the planar words are [`ObjectiveKind::describe`]);
/// `None` when `kind` is planar only.
pub fn describe_tet(kind: ObjectiveKind) -> Option<&'static str> {
    tet_form(kind).map(|o| o.describe())
}
