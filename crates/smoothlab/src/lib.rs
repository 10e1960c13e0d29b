//! smoothlab: a mesh-smoothing laboratory.
//!
//! The core is pure Rust with no web types. Modules follow the mathematics, each using
//! only those before it (the order is the table in `ARCHITECTURE.md`, checked by a test):
//! [`numeric`] (scale and robust numerics, the one random generator) → [`mesh`] (model
//! and topology) → [`quality`] (element metrics) → [`objective`] (a node's objective over
//! its star) → [`optimize`] (solvers) → [`smooth`] (drivers: Laplacian, smart, combined,
//! rules with priority) → [`render`] (tiny-skia) → [`surface`] and [`volume`] (3D) →
//! [`model`] (what a file holds) → [`generate`] (sample meshes) → [`io`] (mesh files) →
//! [`lab`] (the page's state). The wasm layer (`wasm`, only on `wasm32`) converts types
//! and calls the core.
//!
//! # Read, smooth, measure
//! A mesh from text (here a legacy VTK file: four triangles round one free node, pulled
//! off-centre), three passes of Chen, Tristano & Kwok's algorithm (the new objective,
//! their rules, priority order), and the statistics the papers judge by:
//! ```
//! use smoothlab::io::{read_str, write_string, Format, WriteOptions};
//! use smoothlab::objective::{objective, ObjectiveKind};
//! use smoothlab::quality::mesh_stats;
//! use smoothlab::smooth::{smooth, SmoothOptions};
//!
//! let vtk = "# vtk DataFile Version 3.0\nstar\nASCII\nDATASET UNSTRUCTURED_GRID\n\
//!            POINTS 5 double\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.8 0.7 0\n\
//!            CELLS 4 16\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\nCELL_TYPES 4\n5\n5\n5\n5\n";
//! let mut mesh = read_str(vtk, Format::Vtk)?;
//! assert_eq!((mesh.node_count(), mesh.element_count()), (5, 4));
//! let before = mesh_stats(&mesh);
//!
//! let new = objective(ObjectiveKind::New);
//! let records = smooth(&mut mesh, new.as_ref(), SmoothOptions::default(), 3, &|| 0.0)?;
//! assert_eq!(records.len(), 3);
//!
//! // the boundary is fixed; the free node goes to the centre, where every angle is 45° or 90°
//! let after = mesh_stats(&mesh);
//! assert!(after.min_angle_deg > before.min_angle_deg);
//! assert!((mesh.nodes()[4] - glam::DVec2::splat(0.5)).length() < 1e-3);
//! assert!((after.min_angle_deg - 45.0).abs() < 0.1);
//!
//! let text = write_string(&mesh, Format::Vtk, &WriteOptions::default())?;
//! assert!(text.starts_with("# vtk DataFile"));
//! # Ok::<(), smoothlab::Error>(())
//! ```
//!
//! # Draw a mesh
//! [`render::render_mesh`] draws a mesh coloured by quality into a tiny-skia pixmap (the
//! CLI saves it as PNG, the page copies it into a canvas):
//! ```
//! use smoothlab::render::{render_mesh, MeshView};
//!
//! let mesh = smoothlab::generate::rand2d(60, 6, 1)?;
//! let mut pixmap = tiny_skia::Pixmap::new(320, 240).unwrap();
//! render_mesh(&mut pixmap, &mesh, &MeshView::default());
//! let colours: std::collections::HashSet<&[u8]> = pixmap.data().chunks_exact(4).collect();
//! assert!(colours.len() > 10, "a coloured picture, not a blank one");
//! # Ok::<(), smoothlab::Error>(())
//! ```

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
pub mod volume;

pub use error::{Error, Result};
pub use mesh::{ElementKind, Mesh, MeshBuilder};
