//! The core's one call (`smoothlab::read`, `Model::smooth`, `smoothlab::write`) writes
//! what `smoothlab smooth IN -o OUT` writes, byte for byte, on a planar mesh, a surface
//! and a volume mesh.

use crate::common::{ok, p, scratch};

/// The program of the core's front page, on `input`, writing `output`.
fn smooth_in_rust(input: &std::path::Path, output: &std::path::Path) -> smoothlab::Result<String> {
    let mut mesh = smoothlab::read(input)?;
    let report = mesh.smooth(&smoothlab::Smoothing::default())?;
    let line = format!("{} inverted after {} passes", report.inverted(), report.passes().len());
    smoothlab::write(&mesh, output)?;
    Ok(line)
}

#[test]
fn one_call_writes_the_command_lines_bytes_for_every_mesh_kind() {
    let d = scratch("front-door", "kinds");
    let cases: [(&str, &[&str]); 3] = [
        ("plate", &["generate", "plate", "--kind", "mixed"]),
        ("sphere", &["generate", "sphere"]),
        ("block", &["generate", "hexgrid", "--cells", "3"]),
    ];
    for (name, args) in cases {
        let made = d.join(format!("{name}.vtk"));
        let input = d.join(format!("{name}-tangled.vtk"));
        let mut a = args.to_vec();
        a.extend(["-o", p(&made)]);
        ok(&a);
        ok(&["generate", "perturb", p(&made), "--amount", "0.4", "--seed", "3", "-o", p(&input)]);
        let by_cli = d.join(format!("{name}-cli.vtk"));
        let by_rust = d.join(format!("{name}-rust.vtk"));
        ok(&["smooth", p(&input), "-o", p(&by_cli)]);
        let line = smooth_in_rust(&input, &by_rust).unwrap();
        // three passes, then the finish's three on the mesh they leave valid
        assert!(line.ends_with("0 inverted after 6 passes"), "{name}: {line}");
        let (cli, rust) = (std::fs::read(&by_cli).unwrap(), std::fs::read(&by_rust).unwrap());
        assert!(cli == rust, "{name}: the one call wrote other bytes than the command line");
    }
}

#[test]
fn settings_that_do_not_fit_the_mesh_are_refused_in_words() {
    let d = scratch("front-door", "refused");
    let block = d.join("block.vtk");
    ok(&["generate", "hexgrid", "--cells", "2", "-o", p(&block)]);
    let mut mesh = smoothlab::read(&block).unwrap();
    let e = mesh.smooth(&smoothlab::Smoothing::default().slide_curves(true)).unwrap_err();
    assert!(e.to_string().starts_with("slide_curves: "), "{e}");
    let e = mesh.smooth(&smoothlab::Smoothing::default().passes(0)).unwrap_err();
    assert!(e.to_string().starts_with("passes: 0 asked"), "{e}");
}
