//! `smoothlab stats MESH [--json]`.

use std::path::PathBuf;

use clap::Args;
use smoothlab::quality::MeshStats;

#[derive(Args)]
pub struct StatsArgs {
    /// The mesh file
    pub mesh: PathBuf,
    /// Print one JSON object instead of a table
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: StatsArgs) -> Result<(), String> {
    let s = crate::files::read_model(&a.mesh)?.stats();
    if a.json {
        println!("{}", serde_json::to_string(&s).map_err(|e| e.to_string())?);
    } else {
        print!("{}", table(&s));
    }
    Ok(())
}

/// The human-readable table.
pub fn table(s: &MeshStats) -> String {
    let mut t = String::new();
    let mut row = |k: &str, v: String| t.push_str(&format!("{k:<16} {v}\n"));
    if let Some(d) = s.max_distance_from_surface {
        row(
            "surface",
            format!("in 3D, each element measured in its own plane; nodes at most {d:.3e} from the surface"),
        );
    }
    let following =
        if s.following_nodes > 0 { format!(", {} mid-side following", s.following_nodes) } else { String::new() };
    row("nodes", format!("{} ({} free, {} fixed{following})", s.nodes, s.free_nodes, s.fixed_nodes));
    let solid = s.is_volume();
    if solid {
        // each kind with its count, its name saying its nodes: "384 4-node tetrahedra";
        // "940 (445 4-node tetrahedra, 305 8-node hexahedra, 190 5-node pyramids)"
        let words = s.volume_kinds.words();
        row("elements", if s.volume_kinds.present().count() == 1 { words } else { format!("{} ({words})", s.elements) });
    } else {
        row(
            "elements",
            format!(
                "{} ({}, {}, {} quadratic)",
                s.elements,
                crate::args::count(s.triangles, "triangle", "triangles"),
                crate::args::count(s.quads, "quad", "quads"),
                s.quadratic
            ),
        );
    }
    match &s.solid {
        Some(v) if s.volume_kinds.present().any(|(k, _)| !k.is_tet()) => row(
            "inverted",
            format!("{} ({} inside, every corner positive)", s.inverted, v.inverted_inside),
        ),
        _ => row("inverted", s.inverted.to_string()),
    }
    row(
        if solid { "dihedral angles" } else { "angles" },
        format!("min {:.2}°  max {:.2}°", s.min_angle_deg, s.max_angle_deg),
    );
    row(
        if solid { "mean ratio" } else { "quality α/β" },
        format!("min {:.4}  mean {:.4}", s.min_quality, s.mean_quality),
    );
    row(
        "condition κ",
        if s.max_condition.is_finite() {
            format!("max {:.4}", s.max_condition)
        } else {
            "max ∞ (inverted elements)".into()
        },
    );
    if let Some(v) = &s.solid {
        row("scaled Jacobian", format!("min {:.4}", v.min_scaled_jacobian));
    }
    let total: u64 = s.angle_histogram_6deg.iter().sum();
    t.push_str(if solid {
        "dihedral angle histogram (6° bins, % of dihedral angles):\n"
    } else {
        "angle histogram (6° bins, % of corner angles):\n"
    });
    for (i, &c) in s.angle_histogram_6deg.iter().enumerate() {
        if c == 0 {
            continue;
        }
        let pct = 100.0 * c as f64 / total.max(1) as f64;
        let bar = "#".repeat((pct / 2.0).ceil() as usize);
        t.push_str(&format!("  {:>3}–{:<3}° {:>6.2}% {bar}\n", i * 6, i * 6 + 6, pct));
    }
    t
}
