//! What several sections read: the meshes' seed, the median, number formats, JSON files.

/// The seed of every benchmark mesh (the browser bench uses the same).
pub(crate) const SEED: u64 = 2003;

pub(crate) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

pub(crate) fn fmt_ns(v: f64) -> String {
    if v >= 1e4 {
        format!("{:.1} µs", v / 1e3)
    } else if v >= 100.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

pub(crate) fn fmt_ms(ms: f64) -> String {
    if ms >= 1000.0 {
        format!("{:.2} s", ms / 1000.0)
    } else if ms >= 10.0 {
        format!("{ms:.0} ms")
    } else {
        format!("{ms:.1} ms")
    }
}

/// ✓, or ✗ and by how much the figure misses an upper bound.
pub(crate) fn target_mark(got: f64, limit: f64) -> String {
    if got.is_nan() {
        "not measured".into()
    } else if got <= limit {
        "✓".into()
    } else {
        format!("✗ ({:.2}× the target)", got / limit)
    }
}

pub(crate) fn read_json(path: Option<&str>) -> Option<serde_json::Value> {
    serde_json::from_str(&std::fs::read_to_string(path?).ok()?).ok()
}
