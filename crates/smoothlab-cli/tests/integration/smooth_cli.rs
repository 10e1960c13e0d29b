//! `smoothlab smooth`: the JSON report's shape, its `final` object against
//! `smoothlab stats --json` of the written file, the human summary, and the refusals.

use std::path::{Path, PathBuf};

use crate::common::{ok, p, run};
use serde_json::Value;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "smoothlab-smooth-cli-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A mixed plate perturbed until it has inverted elements.
fn tangled_plate(d: &Path) -> PathBuf {
    let plate = d.join("plate.vtk");
    let tangled = d.join("tangled.vtk");
    ok(&["generate", "plate", "--kind", "mixed", "-o", p(&plate)]);
    ok(&[
        "generate",
        "perturb",
        p(&plate),
        "--amount",
        "0.6",
        "--seed",
        "2",
        "-o",
        p(&tangled),
    ]);
    let s: Value = serde_json::from_str(&ok(&["stats", "--json", p(&tangled)])).unwrap();
    assert!(
        s["inverted"].as_u64().unwrap() > 0,
        "the perturbed plate must be tangled: {s}"
    );
    tangled
}

const PASS_FIELDS: [&str; 14] = [
    "pass",
    "moves",
    "stats_ms",
    "untangle_sweeps",
    "visits",
    "inverted",
    "min_angle_deg",
    "max_angle_deg",
    "min_quality",
    "objective_total",
    "laplacian_moves",
    "optimization_calls",
    "solver_iterations",
    "elapsed_ms",
];

#[test]
fn json_report_has_its_shape_and_final_equals_stats_of_the_output() {
    let d = dir("json");
    let input = tangled_plate(&d);
    for (out_name, extra) in [
        ("a.vtk", vec![]),
        (
            "b.msh",
            vec![
                "--strategy",
                "c2",
                "--objective",
                "old",
                "--threshold",
                "15",
                "--passes",
                "2",
            ],
        ),
        (
            "c.vtk",
            vec![
                "--strategy",
                "opt",
                "--objective",
                "condition-max",
                "--order",
                "priority",
                "--max-iter",
                "5",
            ],
        ),
        (
            "d.msh",
            vec![
                "--strategy",
                "laplace",
                "--objective",
                "untangle-mindet",
                "--passes",
                "1",
            ],
        ),
    ] {
        let out = d.join(out_name);
        let mut args = vec!["smooth", p(&input), "-o", p(&out), "--json"];
        args.extend(extra.iter().copied());
        let text = ok(&args);
        assert_eq!(
            text.trim().lines().count(),
            1,
            "one JSON object on one line: {text}"
        );
        let v: Value = serde_json::from_str(&text).unwrap();
        let keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
        let mut sorted = keys.clone();
        sorted.sort_unstable();
        assert_eq!(
            sorted,
            [
                "final",
                "finish",
                "objective",
                "passes",
                "strategy",
                "target",
                "time_ms",
                "untangling_impossible"
            ],
            "{out_name}"
        );
        let passes = v["passes"].as_array().unwrap();
        let want = extra
            .iter()
            .position(|a| *a == "--passes")
            .map_or(3, |i| extra[i + 1].parse::<usize>().unwrap());
        // the finish's passes follow where the passes asked for left the mesh valid
        let finish = v["finish"].as_u64().unwrap() as usize;
        let valid = passes[want - 1]["inverted"] == 0;
        assert_eq!(finish, if valid { 3 } else { 0 }, "{out_name}");
        assert_eq!(passes.len(), want + finish, "{out_name}");
        for (i, rec) in passes.iter().enumerate() {
            let o = rec.as_object().unwrap();
            assert_eq!(o.len(), PASS_FIELDS.len(), "{out_name}: {rec}");
            for f in PASS_FIELDS {
                assert!(
                    o.contains_key(f),
                    "{out_name}: pass record without {f}: {rec}"
                );
            }
            assert_eq!(rec["pass"].as_u64(), Some(i as u64 + 1));
            assert!(rec["elapsed_ms"].as_f64().unwrap() >= 0.0);
        }
        assert!(v["time_ms"].as_f64().unwrap() >= 0.0);
        // `final` is exactly `stats --json` of the written file
        let stats: Value = serde_json::from_str(&ok(&["stats", "--json", p(&out)])).unwrap();
        assert_eq!(v["final"], stats, "{out_name}");
        // and the last pass describes the same mesh
        let last = passes.last().unwrap();
        assert_eq!(last["inverted"], stats["inverted"], "{out_name}");
        assert_eq!(last["min_angle_deg"], stats["min_angle_deg"], "{out_name}");
        assert_eq!(last["min_quality"], stats["min_quality"], "{out_name}");
    }
}

#[test]
fn defaults_are_new_rules_priority_three_passes_and_untangle_the_plate() {
    let d = dir("defaults");
    let input = tangled_plate(&d);
    let out = d.join("s.vtk");
    let v: Value =
        serde_json::from_str(&ok(&["smooth", p(&input), "-o", p(&out), "--json"])).unwrap();
    assert_eq!(v["objective"], "new");
    assert_eq!(v["strategy"], "rules");
    let passes = v["passes"].as_array().unwrap();
    // three passes, then the finish's three on the valid mesh they leave
    assert_eq!(passes.len(), 6);
    assert_eq!(v["finish"], 3);
    // priority order visits poor nodes more than once a pass
    let free = v["final"]["free_nodes"].as_u64().unwrap();
    assert!(
        passes[0]["visits"].as_u64().unwrap() > free,
        "{}",
        passes[0]
    );
    assert_eq!(
        v["final"]["inverted"], 0,
        "new + rules untangles this plate in 3 passes"
    );
    // the same with --order input visits each free node once, then again only in
    // untangling sweeps (while elements are inverted)
    let v: Value = serde_json::from_str(&ok(&[
        "smooth",
        p(&input),
        "-o",
        p(&out),
        "--json",
        "--order",
        "input",
    ]))
    .unwrap();
    let first = &v["passes"][0];
    let (visits, sweeps) = (
        first["visits"].as_u64().unwrap(),
        first["untangle_sweeps"].as_u64().unwrap(),
    );
    assert!(visits >= free && (visits > free) == (sweeps > 0), "{first}");
    assert!(sweeps <= u64::from(smoothlab::smooth::UNTANGLE_SWEEPS));
    // other strategies default to input order
    let v: Value = serde_json::from_str(&ok(&[
        "smooth",
        p(&input),
        "-o",
        p(&out),
        "--json",
        "--strategy",
        "smart",
    ]))
    .unwrap();
    assert_eq!(v["passes"][0]["visits"].as_u64(), Some(free));
    assert_eq!(v["passes"][0]["optimization_calls"], 0);
}

#[test]
fn human_summary_has_a_line_per_pass_and_writes_the_mesh() {
    let d = dir("human");
    let input = tangled_plate(&d);
    let out = d.join("s.msh");
    let text = ok(&[
        "smooth",
        p(&input),
        "-o",
        p(&out),
        "--passes",
        "4",
        "--strategy",
        "laplace",
    ]);
    assert_eq!(
        text.lines().filter(|l| l.starts_with("pass ")).count(),
        4,
        "{text}"
    );
    assert!(
        text.contains("measured only"),
        "laplace says it ignores the objective: {text}"
    );
    assert!(text.lines().last().unwrap().starts_with("final:"), "{text}");
    assert!(out.is_file());
}

#[test]
fn bad_options_are_refused_with_a_message_and_nothing_written() {
    let d = dir("bad");
    let input = tangled_plate(&d);
    let out = d.join("never.vtk");
    let i = p(&input);
    let o = p(&out);
    for (args, says) in [
        (vec!["--passes", "0"], "--passes"),
        (vec!["--max-iter", "0"], "--max-iter"),
        (vec!["--strategy", "c1", "--threshold", "0"], "--threshold"),
        (
            vec!["--strategy", "c3", "--threshold", "90.5"],
            "--threshold",
        ),
        (
            vec!["--strategy", "c2", "--threshold", "NaN"],
            "--threshold",
        ),
        (vec!["--threshold", "20"], "c1, c2 and c3"),
        (
            vec!["--strategy", "opt", "--threshold", "20"],
            "c1, c2 and c3",
        ),
        (
            vec!["--strategy", "laplace", "--max-iter", "5"],
            "never calls the solver",
        ),
        (
            vec!["--strategy", "smart", "--max-iter", "5"],
            "never calls the solver",
        ),
        (vec!["--objective", "best"], "best"),
        (vec!["--strategy", "fast"], "fast"),
        (vec!["--order", "random"], "random"),
        (vec!["--passes", "-1"], "-1"),
        (
            vec!["--strategy", "c2", "--target", "input"],
            "Laplacian steps",
        ),
        (vec!["--target", "mesh"], "mesh"),
    ] {
        let mut a = vec!["smooth", i, "-o", o];
        a.extend(args.iter().copied());
        let r = run(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(!r.status.success(), "{args:?} must fail");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(r.stdout.is_empty(), "{args:?}: nothing on stdout");
        assert!(!out.exists(), "{args:?}: no output written");
    }
    // unreadable input and unknown output format name the file
    let r = run(&["smooth", p(&d.join("missing.vtk")), "-o", o]);
    assert!(!r.status.success() && String::from_utf8_lossy(&r.stderr).contains("missing.vtk"));
    let r = run(&["smooth", i, "-o", p(&d.join("out.xyz"))]);
    assert!(!r.status.success() && String::from_utf8_lossy(&r.stderr).contains("out.xyz"));
}

#[test]
fn pass_through_folds_is_an_option_of_the_solver_strategies_only() {
    let d = dir("folds");
    let mesh = tangled_plate(&d);
    let out = d.join("out.vtk");
    let json = ok(&[
        "smooth",
        p(&mesh),
        "-o",
        p(&out),
        "--objective",
        "untangle",
        "--strategy",
        "opt",
        "--passes",
        "2",
        "--pass-through-folds",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let finish = v["finish"].as_u64().unwrap() as usize;
    assert_eq!(v["passes"].as_array().unwrap().len(), 2 + finish);
    let r = run(&[
        "smooth",
        p(&mesh),
        "-o",
        p(&out),
        "--strategy",
        "laplace",
        "--pass-through-folds",
    ]);
    assert!(!r.status.success());
    assert!(String::from_utf8_lossy(&r.stderr).contains("--pass-through-folds"));
}

#[test]
fn no_pass_through_folds_and_the_penalty_design_are_options_too() {
    let d = dir("penalty");
    let mesh = tangled_plate(&d);
    let out = d.join("out.vtk");
    let json = |extra: &[&str]| -> Value {
        let mut args = vec!["smooth", p(&mesh), "-o", p(&out), "--passes", "1", "--json"];
        args.extend_from_slice(extra);
        serde_json::from_str(&ok(&args)).unwrap()
    };
    // the penalty design changes the result; the default is the barrier
    let default = json(&[]);
    assert_eq!(json(&["--penalty", "barrier"])["final"], default["final"]);
    assert_ne!(json(&["--penalty", "angle"])["final"], default["final"]);
    // the default passes through folds for `new`: forcing it on changes nothing, off does
    assert_eq!(json(&["--pass-through-folds"])["final"], default["final"]);
    assert_ne!(
        json(&["--no-pass-through-folds"])["final"],
        default["final"]
    );
    // refused where it would do nothing, or with an unknown design
    for (args, says) in [
        (
            vec!["--objective", "old", "--penalty", "angle"],
            "--objective new",
        ),
        (vec!["--penalty", "cubic"], "cubic"),
        (
            vec!["--strategy", "smart", "--no-pass-through-folds"],
            "--no-pass-through-folds",
        ),
    ] {
        let mut all = vec!["smooth", p(&mesh), "-o", p(&out)];
        all.extend(args.iter().copied());
        let r = run(&all);
        assert!(!r.status.success(), "{args:?}");
        assert!(
            String::from_utf8_lossy(&r.stderr).contains(says),
            "{args:?}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
    }
}

/// Three triangles, every node fixed by the file; the third is clockwise (inverted), and
/// the fourth has two fixed nodes at one point.
const STUCK_VTK: &str = "# vtk DataFile Version 3.0
inverted corners of fixed nodes, and coincident fixed nodes
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 7 double
0.2 0.2 0
1 0 0
0 1 0
-1 0 0
0 -1 0
1 1 0
1 1 0
CELLS 5 20
3 0 1 2
3 0 2 3
3 1 4 3
3 1 5 2
3 0 6 5
CELL_TYPES 5
5 5 5 5 5
POINT_DATA 7
SCALARS fixed int 1
LOOKUP_TABLE default
0 1 1 1 1 1 1
";

#[test]
fn smooth_names_the_elements_it_cannot_untangle_and_why() {
    let d = dir("stuck");
    let input = d.join("stuck.vtk");
    std::fs::write(&input, STUCK_VTK).unwrap();
    let out = d.join("out.vtk");
    let text = ok(&["smooth", p(&input), "-o", p(&out)]);
    assert!(
        text.contains("untangling is impossible for 2 of the 2 inverted elements"),
        "{text}"
    );
    assert!(text.contains("element 2: its corner at node"), "{text}");
    assert!(text.contains("all fixed"), "{text}");
    assert!(
        text.contains("element 4: nodes 6 and 5 are fixed and at the same point"),
        "{text}"
    );
    let v: Value =
        serde_json::from_str(&ok(&["smooth", p(&input), "-o", p(&out), "--json"])).unwrap();
    let list = v["untangling_impossible"].as_array().unwrap();
    assert_eq!(
        list.iter()
            .map(|o| o["element"].as_u64().unwrap())
            .collect::<Vec<_>>(),
        [2, 4]
    );
    // a mesh that untangles reports none
    let plate = tangled_plate(&d);
    let v: Value =
        serde_json::from_str(&ok(&["smooth", p(&plate), "-o", p(&out), "--json"])).unwrap();
    assert_eq!(v["final"]["inverted"], 0);
    assert_eq!(v["untangling_impossible"], serde_json::json!([]));
}

/// Issue 29 (cosmetic): `smooth --help` gave `--slide-curves` the text of `--json` and
/// `--json` none; `stats` said "1 tetrahedra".
#[test]
fn help_texts_are_their_own_and_counts_agree_with_their_nouns() {
    let help = ok(&["smooth", "--help"]);
    let text_of = |flag: &str| {
        let at = help
            .find(&format!("--{flag}\n"))
            .unwrap_or_else(|| panic!("no --{flag} in:\n{help}"));
        help[at..]
            .lines()
            .nth(1)
            .unwrap_or_default()
            .trim()
            .to_string()
    };
    assert!(
        text_of("json").starts_with("Print one JSON object"),
        "{}",
        text_of("json")
    );
    assert!(
        text_of("slide-curves").starts_with("A surface's feature curves"),
        "{}",
        text_of("slide-curves")
    );
    let d = dir("plurals");
    let one = d.join("one.vtk");
    std::fs::write(
        &one,
        "# vtk DataFile Version 2.0\none\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n\
         CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n",
    )
    .unwrap();
    let stats = ok(&["stats", p(&one)]);
    assert!(
        stats.contains("elements         1 4-node tetrahedron\n"),
        "{stats}"
    );
    let cube = d.join("cube.vtk");
    ok(&["generate", "cube", "--cells", "1", "-o", p(&cube)]);
    assert!(ok(&["stats", p(&cube)]).contains("6 4-node tetrahedra"));
}

/// `--target input` on a valid graded mesh: the passes keep each corner's shape (no node
/// moves with `--finish 0`), the summary and `--json` name the target, and against the
/// ideal the same mesh's stretched rows move.
#[test]
fn the_input_target_keeps_a_valid_graded_mesh() {
    let d = dir("target");
    let input = d.join("graded.vtk");
    // 6 × 4 quads, rows graded ×1.5 from y = 0, squeezed to a tenth of the width
    let ys = [0.0, 0.01, 0.025, 0.0475, 0.08125];
    let mut vtk = String::from(
        "# vtk DataFile Version 3.0\ngraded\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 35 double\n",
    );
    for (j, y) in ys.iter().enumerate() {
        for i in 0..7 {
            // interior nodes off the grid a little, so the ideal has work to do
            let dx = if (1..6).contains(&i) && (1..4).contains(&j) {
                0.02 * ((i + j) % 3) as f64 - 0.02
            } else {
                0.0
            };
            vtk.push_str(&format!("{} {y} 0\n", i as f64 / 6.0 + dx));
        }
    }
    vtk.push_str("CELLS 24 120\n");
    for j in 0..4 {
        for i in 0..6 {
            let a = j * 7 + i;
            vtk.push_str(&format!("4 {a} {} {} {}\n", a + 1, a + 8, a + 7));
        }
    }
    vtk.push_str("CELL_TYPES 24\n");
    vtk.push_str(&"9\n".repeat(24));
    std::fs::write(&input, vtk).unwrap();
    let kept = d.join("kept.vtk");
    let text = ok(&[
        "smooth",
        p(&input),
        "-o",
        p(&kept),
        "--target",
        "input",
        "--finish",
        "0",
    ]);
    assert!(
        text.starts_with("smoothing: strategy rules, objective new against the input target"),
        "{text}"
    );
    let same = d.join("same.vtk");
    ok(&["convert", p(&input), p(&same)]);
    assert_eq!(
        std::fs::read_to_string(&kept).unwrap(),
        std::fs::read_to_string(&same).unwrap()
    );
    let json = ok(&[
        "smooth",
        p(&input),
        "-o",
        p(&kept),
        "--target",
        "input",
        "--json",
    ]);
    let v: Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["target"], "input");
    let moved = d.join("moved.vtk");
    ok(&["smooth", p(&input), "-o", p(&moved), "--finish", "0"]);
    assert_ne!(
        std::fs::read_to_string(&moved).unwrap(),
        std::fs::read_to_string(&same).unwrap()
    );
}
