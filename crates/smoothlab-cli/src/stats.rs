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
    // an element's mean ratio is its corners' mean: beside inverted elements a positive
    // smallest one says so (a hexahedron with one corner inverted keeps a positive mean)
    let averaged = if solid && s.inverted > 0 && s.min_quality > 0.0 { " (corners averaged)" } else { "" };
    row(
        if solid { "mean ratio" } else { "quality α/β" },
        format!("min {:.4}{averaged}  mean {:.4}", s.min_quality, s.mean_quality),
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
    let sizes = if solid { "volumes" } else { "areas" };
    row(
        "grading",
        match s.grading {
            Some(g) => format!("max {g:.4} (the largest ratio of two neighbours' {sizes})"),
            None => "none (no two valid elements are neighbours)".into(),
        },
    );
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

#[cfg(test)]
mod tests {
    use super::*;
    use smoothlab::generate::{hex_grid, perturb_volume, HexBlock};
    use smoothlab::objective::{solid_objective, ObjectiveKind};
    use smoothlab::smooth::SmoothOptions;
    use smoothlab::volume::{smooth_volume, volume_stats};

    fn mean_ratio_line(s: &MeshStats) -> String {
        table(s).lines().find(|l| l.starts_with("mean ratio")).unwrap().to_string()
    }

    /// Beside inverted elements a positive smallest mean ratio says it averages corners
    /// (issue: the tangled block of hexahedra after one pass of the old objective, 63
    /// inverted, min mean ratio 0.0122); a valid mesh, or a negative one, needs no word.
    #[test]
    fn a_positive_mean_ratio_beside_inverted_elements_says_why() {
        let valid = volume_stats(&hex_grid(&HexBlock::cube(2)).unwrap());
        assert!(!mean_ratio_line(&valid).contains("averaged"), "{}", mean_ratio_line(&valid));
        // the tangled block as the page opens it: its smallest mean ratio is negative
        let mut m = perturb_volume(&hex_grid(&HexBlock::cube(6)).unwrap(), 1.0, 1).unwrap();
        let tangled = volume_stats(&m);
        assert!(tangled.inverted > 0 && tangled.min_quality < 0.0);
        assert!(!mean_ratio_line(&tangled).contains("averaged"), "{}", mean_ratio_line(&tangled));
        // one pass of the old objective: inverted elements, every element's mean positive
        let old = solid_objective(ObjectiveKind::MaxMinShape).unwrap();
        smooth_volume(&mut m, &*old, SmoothOptions::default(), 1, &|| 0.0).unwrap();
        let s = volume_stats(&m);
        assert!(s.inverted > 0 && s.min_quality > 0.0, "{} inverted, min {}", s.inverted, s.min_quality);
        let line = mean_ratio_line(&s);
        assert!(line.contains(&format!("min {:.4} (corners averaged)  mean", s.min_quality)), "{line}");
    }
}
