//! `smoothlab stats --json` checked against an independent computation: angles from the
//! law of cosines, α from Heron's formula, β from its four triangles, κ from the 2×2
//! matrix algebra written out by hand — none of it through the library's code.

use std::path::PathBuf;
use std::process::Command;
use crate::common::{bin};

fn tmp(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("smoothlab-cli-stats-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn stats_json(path: &PathBuf) -> serde_json::Value {
    let out = Command::new(bin()).arg("stats").arg(path).arg("--json").output().unwrap();
    assert!(out.status.success(), "stats failed: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

type P = (f64, f64);

fn dist(a: P, b: P) -> f64 {
    ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt()
}

/// Interior angle at `b` of triangle a-b-c by the law of cosines, degrees (unsigned).
fn angle_deg(a: P, b: P, c: P) -> f64 {
    let (x, y, z) = (dist(a, b), dist(b, c), dist(a, c));
    ((x * x + y * y - z * z) / (2.0 * x * y)).clamp(-1.0, 1.0).acos().to_degrees()
}

/// Lo's α by Heron's area (for a CCW triangle).
fn alpha_heron(a: P, b: P, c: P) -> f64 {
    let (x, y, z) = (dist(a, b), dist(b, c), dist(c, a));
    let s = (x + y + z) / 2.0;
    let area = (s * (s - x) * (s - y) * (s - z)).max(0.0).sqrt();
    4.0 * 3f64.sqrt() * area / (x * x + y * y + z * z)
}

/// κ of the triangle corner at `a` weighted by the ideal triangle, written out:
/// T = A W⁻¹, W⁻¹ = [[1, −1/√3], [0, 2/√3]], κ = |T|²_F / det T.
fn kappa_tri(a: P, b: P, c: P) -> f64 {
    let (a11, a21) = (b.0 - a.0, b.1 - a.1);
    let (a12, a22) = (c.0 - a.0, c.1 - a.1);
    let s = 1.0 / 3f64.sqrt();
    let t11 = a11;
    let t21 = a21;
    let t12 = -a11 * s + a12 * 2.0 * s;
    let t22 = -a21 * s + a22 * 2.0 * s;
    (t11 * t11 + t12 * t12 + t21 * t21 + t22 * t22) / (t11 * t22 - t12 * t21)
}

fn vtk(points: &[P], cells: &[&[usize]], types: &[u32]) -> String {
    let mut s = String::from("# vtk DataFile Version 3.0\nhand-made\nASCII\nDATASET UNSTRUCTURED_GRID\n");
    s += &format!("POINTS {} double\n", points.len());
    for p in points {
        s += &format!("{} {} 0\n", p.0, p.1);
    }
    let size: usize = cells.iter().map(|c| c.len() + 1).sum();
    s += &format!("CELLS {} {}\n", cells.len(), size);
    for c in cells {
        s += &format!("{} {}\n", c.len(), c.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(" "));
    }
    s += &format!("CELL_TYPES {}\n", types.len());
    for t in types {
        s += &format!("{t}\n");
    }
    s
}

fn close(v: &serde_json::Value, key: &str, want: f64, tol: f64) {
    let got = v[key].as_f64().unwrap_or_else(|| panic!("{key} missing or not a number: {v}"));
    assert!((got - want).abs() <= tol, "{key}: got {got}, independent value {want}");
}

#[test]
fn stats_json_agrees_with_independent_formulas_on_a_triangle_fan() {
    // a hexagonal fan with the centre pulled off-centre: six different triangles
    let c = (0.31, -0.17);
    let ring: Vec<P> = (0..6).map(|i| {
        let t = i as f64 * std::f64::consts::PI / 3.0;
        (t.cos() * (1.0 + 0.1 * i as f64), t.sin())
    }).collect();
    let mut pts = vec![c];
    pts.extend(&ring);
    let cells: Vec<Vec<usize>> = (0..6).map(|i| vec![0, 1 + i, 1 + (i + 1) % 6]).collect();
    let cell_refs: Vec<&[usize]> = cells.iter().map(|c| c.as_slice()).collect();
    let path = tmp("fan.vtk", &vtk(&pts, &cell_refs, &[5; 6]));
    let v = stats_json(&path);

    let mut angles = vec![];
    let mut alphas = vec![];
    let mut kappa_max: f64 = 0.0;
    for cell in &cells {
        let [a, b, cc] = [pts[cell[0]], pts[cell[1]], pts[cell[2]]];
        angles.extend([angle_deg(cc, a, b), angle_deg(a, b, cc), angle_deg(b, cc, a)]);
        alphas.push(alpha_heron(a, b, cc));
        kappa_max = kappa_max.max(kappa_tri(a, b, cc)).max(kappa_tri(b, cc, a)).max(kappa_tri(cc, a, b));
    }
    assert_eq!(v["nodes"], 7);
    assert_eq!(v["elements"], 6);
    assert_eq!(v["triangles"], 6);
    assert_eq!(v["quads"], 0);
    assert_eq!(v["quadratic"], 0);
    assert_eq!(v["free_nodes"], 1);
    assert_eq!(v["fixed_nodes"], 6);
    assert_eq!(v["following_nodes"], 0);
    assert_eq!(v["inverted"], 0);
    close(&v, "min_angle_deg", angles.iter().cloned().fold(f64::INFINITY, f64::min), 1e-9);
    close(&v, "max_angle_deg", angles.iter().cloned().fold(0.0, f64::max), 1e-9);
    close(&v, "min_quality", alphas.iter().cloned().fold(f64::INFINITY, f64::min), 1e-12);
    close(&v, "mean_quality", alphas.iter().sum::<f64>() / 6.0, 1e-12);
    close(&v, "max_condition", kappa_max, 1e-9 * kappa_max);
    let hist: Vec<u64> = v["angle_histogram_6deg"].as_array().unwrap().iter().map(|x| x.as_u64().unwrap()).collect();
    assert_eq!(hist.len(), 30);
    let mut want = vec![0u64; 30];
    for a in &angles {
        want[((a / 6.0) as usize).min(29)] += 1;
    }
    assert_eq!(hist, want);
}

#[test]
fn stats_json_on_quads_and_an_inverted_element() {
    // 2×1 quads: a unit square and a sheared one; then fold the second over
    let pts = [(0.0, 0.0), (1.0, 0.0), (2.3, 0.0), (0.0, 1.0), (1.0, 1.0), (2.0, 1.0)];
    let cells: [&[usize]; 2] = [&[0, 1, 4, 3], &[1, 2, 5, 4]];
    let v = stats_json(&tmp("quads.vtk", &vtk(&pts, &cells, &[9, 9])));
    // β of the square is 1; β of the sheared quad: min of its four corner-triangle α over √3/2
    let q = [pts[1], pts[2], pts[5], pts[4]];
    let tri_alpha = |i: usize| alpha_heron(q[(i + 3) % 4], q[i], q[(i + 1) % 4]);
    let beta = (0..4).map(tri_alpha).fold(f64::INFINITY, f64::min) / (3f64.sqrt() / 2.0);
    close(&v, "min_quality", beta.min(1.0), 1e-12);
    close(&v, "mean_quality", (1.0 + beta) / 2.0, 1e-12);
    assert_eq!(v["quads"], 2);
    assert_eq!(v["inverted"], 0);
    close(&v, "min_angle_deg", angle_deg(q[2], q[1], q[0]).min(90.0), 1e-9);

    // node 2 dragged left past node 1: the second quad folds; max_condition is ∞ → null
    let mut bad = pts;
    bad[2] = (0.5, 0.0);
    let v = stats_json(&tmp("folded.vtk", &vtk(&bad, &cells, &[9, 9])));
    assert_eq!(v["inverted"], 1);
    assert!(v["max_condition"].is_null(), "κ of an inverted element is infinite: {}", v["max_condition"]);
    assert!(v["min_quality"].as_f64().unwrap() < 0.0);
    assert!(v["min_angle_deg"].as_f64().unwrap() < 0.0);
}

#[test]
fn stats_human_table_and_errors() {
    let pts = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)];
    let cells: [&[usize]; 1] = [&[0, 1, 2]];
    let out = Command::new(bin()).arg("stats").arg(tmp("one.vtk", &vtk(&pts, &cells, &[5]))).output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success());
    assert!(text.contains("nodes") && text.contains("min 45.00°") && text.contains("max 90.00°"), "{text}");
    let out = Command::new(bin()).arg("stats").arg(tmp("bad.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 0\n1 0 0\n")).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("bad.vtk") && err.contains("line"), "{err}");
    let out = Command::new(bin()).arg("stats").arg("/nonexistent/x.vtk").output().unwrap();
    assert!(!out.status.success());
}

/// A triangle of zero area loads with a warning that names it, and the warning's claim
/// that it counts as inverted agrees with the statistics; a thin but valid triangle is not
/// named.
#[test]
fn zero_area_elements_are_named_and_counted_as_inverted() {
    // element 1 is (1,0)-(2,0)-(3,0): collinear; element 0 is a valid thin sliver
    let text = vtk(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1e-9), (2.0, 0.0), (3.0, 0.0)], &[&[0, 1, 2], &[1, 3, 4]], &[5, 5]);
    let p = tmp("zero-area.vtk", &text);
    let out = Command::new(bin()).arg("stats").arg(&p).arg("--json").output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("1 element(s) of zero area (element 1)") && err.contains("count as inverted"), "{err}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["inverted"], 1, "{v}");
}
