//! Pictures drawn with tiny-skia: pure functions from data and options to pixels in a
//! `&mut tiny_skia::Pixmap`. Nothing here knows about the web; the page and the CLI
//! pass plain data (meshes, sampled fields, paths, series) and get pixels back.
//!
//! - [`render_mesh`]: elements coloured by a quality [`Metric`], inverted elements
//!   hatched, curved quadratic edges, node marks, a highlighted star, a colour bar;
//!   [`pick_node`] maps a click back to a node.
//! - [`render_level_set`]: filled level bands and iso-lines of one node's objective
//!   over its star (Chen et al. 2003, Figs. 7, 10, 20) with the feasible region and the
//!   solver's path; [`render_level_sets_side_by_side`] for old vs new.
//! - [`render_chart`] and [`render_pass_histories`]: convergence histories
//!   (Chen et al. 2003, Figs. 11–12).
//! - [`render_angle_histogram`]: angle distributions (Freitag 1997, Fig. 3).
//! - [`render_compare`]: two mesh panels with titles and statistics.
//! - [`render_sketch`]: a triangle and the lines its free corner moves along, to read a
//!   1-D curve beside (Chen et al. 2003, Figs. 2, 6); [`render_titled`]: panels in a grid.
//! - [`render_surface`]: a surface mesh in 3D seen by an orbit [`Camera`], faces in their
//!   quality colour, shaded and depth-sorted, inverted ones hatched; the returned
//!   [`Projection`] maps points to pixels and picks nodes.
//!
//! Sizes in options are CSS pixels; a device-pixel ratio scales them (see [`view`]).
//! tiny-skia pixels are premultiplied RGBA; every view paints an opaque background, so
//! the bytes can go to a canvas `ImageData` as they are.
//!
//! ```
//! use smoothlab_render::{render_mesh, MeshView};
//!
//! let mesh = smoothlab::generate::rand2d(60, 6, 1)?;
//! let mut pixmap = tiny_skia::Pixmap::new(320, 240).unwrap();
//! render_mesh(&mut pixmap, &mesh, &MeshView::default());
//! let colours: std::collections::HashSet<&[u8]> = pixmap.data().chunks_exact(4).collect();
//! assert!(colours.len() > 10, "a coloured picture, not a blank one");
//! # Ok::<(), smoothlab::Error>(())
//! ```

mod axes;
mod chart;
mod colormap;
mod compare;
mod contour;
mod font;
mod histogram;
pub mod layout;
mod levelset;
mod mesh;
mod paint;
mod profile;
mod text;
mod theme;
pub mod view;
mod view3d;
mod surface_picture;
mod volume_picture;

#[cfg(test)]
mod tests;

pub use axes::{format_power_of_ten, format_tick, log_ticks, nice_range, nice_step, nice_ticks, Axis, Scale, Ticks};
pub use chart::{render_chart, render_pass_histories, render_pass_histories_titled, Chart, PassHistory, Series, PASS_TITLES};
pub use colormap::{bucket, bucket_color, lightness, series_color, Colormap, BUCKETS, SERIES, VIRIDIS};
pub use compare::{render_compare, render_compare_with, CompareBar, ComparePanel, CompareText};
pub use contour::{iso_segments, Grid};
pub use histogram::{percentages, render_angle_histogram, AngleHistogram, HistogramAxis, HistogramSeries};
pub use levelset::{PATH_RGB, 
    choose_levels, feasible_bounds, feasible_bounds_of, level_set_legend_height, level_set_view, render_level_set, render_level_sets_side_by_side, sample_field,
    sample_plane, star_bounds, Field, LevelSet, PlaneFunction, StarFunction,
    LevelSetView, Levels, PathKind,
};
pub use levelset::{feasible_levels, level_set_legend_height_with, render_level_set_with, LevelSetExtras, Overlay};
pub use mesh::{
    bezier_control, colour_bar_band, mesh_colour_bar_shown, mesh_view, pick_node, pick_node_within, render_mesh, MeshView, Metric,
    Show, COLOUR_BAR_SHARE, INVERTED, PICK_RADIUS,
};
pub use paint::Marker;
pub use profile::{render_sketch, render_titled, title_band, Sketch, SketchLine};
/// The pieces of `render_mesh` the page's fast raster view (`lab::raster`) draws with.
pub use mesh::{draw_colour_bar, draw_inverted, draw_sliding_boundary, push_element};
pub use text::{draw_text, draw_text_rotated, text_width, Align, TextStyle, Valign};
pub use surface_picture::{SurfaceFaces, SurfacePicture};
pub use theme::Theme;
pub use volume_picture::{Cut, CutFaces, VolumePicture};
pub use view::{Frame, View, ZoomPan};
pub use view3d::{
    draw_node_mark, newell_normal, render_surface, render_surface_marked, shade, Camera, FaceMarks, Faces, Mark, NodeMark, Projection, SurfaceView, AMBIENT,
    BACK_FACE, DEGREES_PER_PIXEL, MARK_LINE_RGB, MAX_DRAG_PITCH, ZOOM_RANGE,
};

/// The picture as PNG bytes, for the CLI (native builds only: the page hands the
/// pixels to a canvas and needs no PNG codec).
#[cfg(not(target_arch = "wasm32"))]
pub fn encode_png(pixmap: &tiny_skia::Pixmap) -> smoothlab::Result<Vec<u8>> {
    pixmap.encode_png().map_err(|e| smoothlab::Error::Io(format!("cannot encode the picture as PNG: {e}")))
}
