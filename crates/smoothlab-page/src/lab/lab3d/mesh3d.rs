//! What the 3D lab needs of a kind of mesh in space ([`Mesh3d`]).

use glam::{DVec2, DVec3};
use tiny_skia::Pixmap;

use super::super::views::FigureWords;
use super::super::{PassSummary, Settings, Side};
use super::{Histogram3d, NodeSlice};
use smoothlab::error::Result;
use smoothlab::io::Format;
use smoothlab::quality::MeshStats;
use smoothlab::smooth::SmoothOptions;
use smoothlab::volume::BoundaryRule;
use smoothlab::BoundaryReport;
use smoothlab_render::{Projection, SurfaceView};


/// A kind of mesh in space that the 3D lab holds: how it is smoothed a pass at a time,
/// measured, perturbed, drawn and written. [`surface`](super::surface) and [`volume`](super::volume) implement it.
pub trait Mesh3d: Clone + Sized {
    /// The kind's name for the page (`surface`, `volume`).
    const KIND: &'static str;
    /// What the kind is, in words, for messages (`a surface`, `tetrahedra`).
    const WHAT: &'static str;
    /// The formats a side can be written in.
    const EXPORTS: &'static [Format];
    /// The driver of a pass, made from checked options.
    type Smoother;
    /// What a side smooths with (the objective over the kind's stars).
    type Objective: ?Sized;
    /// The plane the view is cut by, where the kind has one (`()` where it has none).
    type Cut: Copy + Default + std::fmt::Debug + PartialEq;

    /// Refuses a mesh the lab cannot hold, saying why (beyond [`MAX_NODES`](super::super::MAX_NODES), checked by
    /// [`Lab3d::new`](super::Lab3d::new)).
    fn check(&self) -> Result<()> {
        Ok(())
    }
    fn node_count(&self) -> usize;
    fn element_count(&self) -> usize;
    /// A driver with the options `o` (checked by [`Settings::smooth_options`]).
    fn smoother(o: SmoothOptions) -> Result<Self::Smoother>;
    /// The objective a side's choice names, for this kind.
    /// A side's objective, or why the kind has none for the side's choice (an objective
    /// without a form on this kind).
    fn objective(settings: &Settings, side: Side) -> Result<Box<Self::Objective>>;
    /// One pass numbered `pass`, with its record; `clock` gives milliseconds.
    fn pass(
        &mut self,
        smoother: &mut Self::Smoother,
        objective: &Self::Objective,
        pass: u32,
        clock: &dyn Fn() -> f64,
    ) -> PassSummary;
    /// Measures every corner against `target` taken from `at` (the mesh as loaded) from
    /// now on ([`Model::set_target`](smoothlab::Model::set_target)'s rule).
    fn aim_at(&mut self, target: smoothlab::target::Target, at: &Self);
    /// Why this mesh's boundary nodes cannot slide ([`BoundaryRule::Slide`]), if they
    /// cannot: the kind's words, or the mesh's (a quadratic volume mesh).
    fn slide_refused(&self) -> Option<String>;
    /// What the boundary nodes do from now on, the boundary as it is now the reference
    /// the sliding nodes stay on; called only with a rule [`slide_refused`](Self::slide_refused)
    /// allows, and only when it changes.
    fn set_boundary_rule(&mut self, _rule: BoundaryRule) {}
    /// What a sliding boundary holds now: its nodes by what they do, and how far the
    /// sliding ones are from the boundary as loaded (the CLI's report); `None` while the
    /// boundary is fixed.
    fn boundary_report(&self) -> Option<BoundaryReport> {
        None
    }
    /// The full statistics.
    fn stats(&self) -> MeshStats;
    /// The mesh perturbed, `amount` mean edge lengths, seeded.
    fn perturbed(&self, amount: f64, seed: u64) -> Result<Self>;
    /// A side's heading: its letter and what it smooths with.
    fn side_title(settings: &Settings, side: Side) -> String;
    /// The same, short.
    fn side_label(settings: &Settings, side: Side) -> String;
    /// The colour bar's label (the quality the pictures are coloured by).
    fn quality_label(&self) -> &'static str;
    /// The values the colour bar's ends stand for.
    fn quality_domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    /// The mesh drawn by the 3D view (cut by `cut` where the kind has one); the projection
    /// it used.
    fn draw(&self, pm: &mut Pixmap, cut: Self::Cut, view: &SurfaceView) -> Projection;
    /// The node under the CSS pixel `at` of a picture drawn with `proj` (and `cut`): the
    /// nearest node of the face drawn there ([`Projection::pick_on_faces`]), or, where the
    /// kind's view shows nodes beside its faces, the nearest within `radius`.
    fn pick(&self, cut: Self::Cut, proj: &Projection, at: DVec2, radius: f64) -> Option<usize>;
    /// Node `n`'s position.
    fn point(&self, n: usize) -> DVec3;
    /// Why node `n` cannot be chosen or moved (no such node, fixed, following its
    /// element's corners), in words; `None` when it is free.
    fn why_not_free(&self, n: usize) -> Option<String>;
    /// The free node with the worst star, as the planar views choose by default.
    fn worst_free_node(&self) -> Option<usize>;
    /// Node `n`'s star as lines in space, to mark a chosen node on the 3D view.
    fn star_lines(&self, n: usize) -> Vec<Vec<DVec3>>;
    /// A free node's objective over a plane through it (the kind's: see [`NodeSlice`]),
    /// with the solve of `objective` from where the node is.
    fn slice<'a>(&self, objective: &'a Self::Objective, node: usize, cut: Self::Cut, options: &SmoothOptions) -> Result<NodeSlice<'a>>;
    /// What the side smooths with, as a summary names it (`old (max-min …)`).
    fn objective_label(settings: &Settings, side: Side) -> String;
    /// Moves free node `node` to `to` as the kind's smoother puts a node (a surface's onto
    /// the surface), the nodes that follow it following.
    fn place_node(&mut self, node: usize, to: DVec3);
    /// What a move of `node` changes, as it is now ([`put_back`](Self::put_back) restores it).
    type Kept;
    fn keep_around(&self, node: usize) -> Self::Kept;
    fn put_back(&mut self, kept: Self::Kept);
    /// The titles of the per-pass chart's four charts (min angle, max angle, min quality,
    /// inverted elements) in the kind's words.
    const PASS_TITLES: [&'static str; 4];
    /// The words of the figure's statistics lines.
    const FIGURE_WORDS: FigureWords;
    /// The histograms of each side's elements the page draws, one entry a measure.
    const HISTOGRAMS: &'static [Histogram3d];
    /// The mesh as the text of a file (one of [`EXPORTS`](Self::EXPORTS)).
    fn write(&self, format: Format) -> Result<String>;
    /// The mesh as arrays: what its `.vtk` text holds ([`smoothlab::io::MeshArrays`]).
    fn arrays(&self) -> smoothlab::io::MeshArrays;
    /// Why a file's points were read as this kind, where that needs saying.
    fn not_planar(&self) -> Option<String> {
        None
    }
    /// What the file held that the lab does not smooth, where that needs saying.
    fn file_note(&self) -> Option<String> {
        None
    }
}
