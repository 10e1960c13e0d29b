//! What the page's statistics tables show of a side: the mesh's statistics and the work
//! of the passes since the last reset.

use serde::Serialize;

use super::stats::QuickStats;
use super::{PassSummary, Side};
use smoothlab::quality::MeshStats;

/// The work a panel's passes did since the last reset: its records, summed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct WorkDone {
    pub passes: usize,
    pub laplacian_moves: u64,
    pub optimization_calls: u64,
    pub solver_iterations: u64,
    /// Smoothing time summed over the passes, milliseconds by the caller's clock.
    pub time_ms: f64,
}

impl WorkDone {
    /// The sums of `records`.
    pub fn of(records: &[PassSummary]) -> WorkDone {
        let sum = |f: fn(&PassSummary) -> u32| records.iter().map(|r| f(r) as u64).sum();
        WorkDone {
            passes: records.len(),
            laplacian_moves: sum(|r| r.counts.laplacian_moves),
            optimization_calls: sum(|r| r.counts.optimization_calls),
            solver_iterations: sum(|r| r.counts.solver_iterations),
            time_ms: records.iter().map(|r| r.elapsed_ms).sum(),
        }
    }
}

/// What a panel's statistics table shows: the mesh now and the work done since the last reset.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PanelStats {
    pub side: Side,
    #[serde(flatten)]
    pub mesh: MeshStats,
    #[serde(flatten)]
    pub work: WorkDone,
}

/// The page's statistics table: [`PanelStats`] with the cheap statistics of
/// [`QuickStats`] in place of the full ones.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PanelTable {
    pub side: Side,
    /// The panel's heading: its letter and what it smooths with ([`Choice::title`](super::Choice::title)).
    pub title: String,
    /// The same, short ([`Choice::label`](super::Choice::label)), for a compact page.
    pub label: String,
    pub nodes: usize,
    pub elements: usize,
    #[serde(flatten)]
    pub mesh: QuickStats,
    /// The rows that need every corner measured, when they were (see [`TableDetail`]).
    pub detail: Option<TableDetail>,
    /// A surface's largest distance of a node from its reference surface; `None` for a
    /// planar mesh.
    pub max_distance_from_surface: Option<f64>,
    /// A volume mesh whose boundary slides: its nodes by what they do and the largest
    /// distance of one from the boundary as loaded (the command-line tool's report,
    /// JSON key `boundary`); `None` otherwise.
    pub boundary: Option<smoothlab::BoundaryReport>,
    #[serde(flatten)]
    pub work: WorkDone,
}

/// Corners under this angle, degrees, count as poor in the table: Freitag (1997) judges
/// meshes by their angle distribution (Fig. 3), and 18° is three of its 6° bins.
pub const SMALL_ANGLE_DEG: f64 = 18.0;

/// Meshes with at most this many elements have their table's [`TableDetail`] measured
/// after every change; larger ones when their charts are drawn (after a run).
pub const DETAIL_MAX_ELEMENTS: usize = 250_000;

/// The rows of the table that come from the full statistics ([`MeshStats`]), which
/// measure every corner's angle and every element's condition number.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TableDetail {
    /// Mean element quality α/β.
    pub mean_quality: f64,
    /// Share of corner angles under [`SMALL_ANGLE_DEG`], 0 to 1 (inverted corners count).
    pub small_angle_share: f64,
    /// Worst condition number κ; `None` when an element is inverted (κ = ∞).
    pub max_condition: Option<f64>,
}

impl TableDetail {
    /// The detail rows of full statistics.
    pub fn of(s: &MeshStats) -> TableDetail {
        let bins = (SMALL_ANGLE_DEG / 6.0) as usize;
        let total: u64 = s.angle_histogram_6deg.iter().sum();
        let small: u64 = s.angle_histogram_6deg.iter().take(bins).sum();
        TableDetail {
            mean_quality: s.mean_quality,
            small_angle_share: if total == 0 { 0.0 } else { small as f64 / total as f64 },
            max_condition: s.max_condition.is_finite().then_some(s.max_condition),
        }
    }
}
