//! smoothlab: mesh smoothing for planar, surface and volume meshes.
//!
//! It holds the smoothers of three papers. Chen, Tristano & Kwok (2003): a smooth objective
//! solved by Fletcher–Reeves, with rules for when to optimize and a worst-first order.
//! Freitag (1997): the max-min objective, the smart Laplacian and the combined schemes.
//! Knupp (1999): the condition number and untangling at element corners.
//!
//! # One call for every mesh
//! [`read`] a file, [`Model::smooth`] it with a [`Smoothing`], [`write`](fn@write) it back. The
//! same program smooths a planar mesh, a surface in 3D and a volume mesh, and writes what
//! `smoothlab smooth IN -o OUT` writes, byte for byte:
//! ```
//! # // a folder of its own, holding in.vtk: four triangles round one free node
//! # fn in_vtk() {
//! #     let dir = std::env::temp_dir().join(format!("smoothlab-doc-{}", std::process::id()));
//! #     std::fs::create_dir_all(&dir).unwrap();
//! #     std::env::set_current_dir(&dir).unwrap();
//! #     std::fs::write("in.vtk", "# vtk DataFile Version 3.0\nstar\nASCII\nDATASET UNSTRUCTURED_GRID\n\
//! #         POINTS 5 double\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.8 0.7 0\n\
//! #         CELLS 4 16\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\nCELL_TYPES 4\n5\n5\n5\n5\n").unwrap();
//! # }
//! fn main() -> smoothlab::Result<()> {
//! #   in_vtk();
//!     let mut mesh = smoothlab::read("in.vtk")?;
//!     let report = mesh.smooth(&smoothlab::Smoothing::default())?;
//!     println!("{} inverted after {} passes", report.inverted(), report.passes().len());
//!     smoothlab::write(&mesh, "out.vtk")
//! }
//! ```
//!
//! # Settings, statistics and a mesh from text
//! A legacy VTK file (four triangles round one free node, pulled off-centre), three passes
//! of Knupp's condition number and the finish, and the statistics `smoothlab stats` prints:
//! ```
//! use smoothlab::{io, ObjectiveKind, Smoothing, Strategy};
//!
//! let vtk = "# vtk DataFile Version 3.0\nstar\nASCII\nDATASET UNSTRUCTURED_GRID\n\
//!            POINTS 5 double\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.8 0.7 0\n\
//!            CELLS 4 16\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\nCELL_TYPES 4\n5\n5\n5\n5\n";
//! let mut model = io::read_model_str(vtk, io::Format::Vtk)?;
//! let before = model.stats();
//!
//! let smoothing = Smoothing::default().strategy(Strategy::Opt).objective(ObjectiveKind::Condition);
//! let report = model.smooth(&smoothing)?;
//! // three passes, then the finish's three on the valid mesh (`Smoothing::finish`)
//! assert_eq!((report.passes().len(), report.finish_passes()), (6, 3));
//! assert_eq!(report.inverted(), 0);
//!
//! // the boundary is fixed; the free node goes to the centre, where every angle is 45° or 90°
//! assert!(report.stats().min_angle_deg > before.min_angle_deg);
//! assert!((report.stats().min_angle_deg - 45.0).abs() < 0.1);
//! # Ok::<(), smoothlab::Error>(())
//! ```
//!
//! # The layers
//! Modules follow the mathematics, each using only those before it: [`numeric`] (scale and
//! robust numerics, the one random generator) → [`mesh`] (model and topology) →
//! [`quality`] (element metrics) → [`objective`] (a node's objective over its star) →
//! [`optimize`] (solvers) → [`smooth`] (drivers: Laplacian, smart, combined, rules with
//! priority) → [`surface`] and [`volume`] (3D) → [`model`] (what a file holds) →
//! [`generate`] (sample meshes) → [`io`] (mesh files). Pictures, the page and the CLI are
//! crates of their own above this one.

/// Declares a fieldless enum together with `ALL`, every variant in declaration order, so
/// a variant added to the enum is in `ALL` (and so in every menu, CLI list and test built
/// from it) without a second edit that could be forgotten.
#[doc(hidden)]
#[macro_export]
macro_rules! enum_with_all {
    ($(#[$m:meta])* $vis:vis enum $name:ident { $($(#[$vm:meta])* $v:ident,)+ }) => {
        $(#[$m])* $vis enum $name { $($(#[$vm])* $v,)+ }
        impl $name {
            /// Every variant, in declaration order.
            pub const ALL: [$name; [$(stringify!($v)),+].len()] = [$($name::$v),+];
        }
    };
}

/// Declares a fieldless enum with `ALL` (as [`enum_with_all!`]) and, from one table, each
/// variant's `name()` (on the command line) and `describe()` (its help): `Tri =>
/// ("tri", "two triangles per square"),`.
#[doc(hidden)]
#[macro_export]
macro_rules! enum_with_names {
    ($(#[$m:meta])* $vis:vis enum $name:ident { $($(#[$vm:meta])* $v:ident => ($s:literal, $d:literal),)+ }) => {
        $crate::enum_with_all! { $(#[$m])* $vis enum $name { $($(#[$vm])* $v,)+ } }
        impl $name {
            /// Its name on the command line.
            pub fn name(self) -> &'static str {
                match self { $($name::$v => $s,)+ }
            }
            /// What it is, in a few words (the command line's help).
            pub fn describe(self) -> &'static str {
                match self { $($name::$v => $d,)+ }
            }
        }
    };
}

pub mod error;
pub mod generate;
pub mod io;
pub mod mesh;
pub mod model;
pub mod numeric;
pub mod objective;
pub mod optimize;
pub mod quality;
pub mod smooth;
pub mod surface;
pub mod target;
pub mod volume;

mod smoothing;

pub use error::{Error, Result};
#[cfg(not(target_arch = "wasm32"))]
pub use io::{read, write};
pub use io::{Format, WriteOptions};
pub use mesh::{ElementKind, Mesh, MeshBuilder, VolumeKind};
pub use model::Model;
pub use objective::{ObjectiveKind, Penalty};
pub use quality::MeshStats;
pub use smooth::{Obstacle, Order, PassRecord, Strategy};
pub use smoothing::{BoundaryReport, Report, Smoothing};
pub use surface::Surface;
pub use target::Target;
pub use volume::VolumeMesh;

/// The README's Rust examples, compiled as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
