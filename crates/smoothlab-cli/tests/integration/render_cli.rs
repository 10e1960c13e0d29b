//! `smoothlab render`: every view writes a PNG of the asked size that is not blank, and
//! bad requests are refused with a message.

use std::path::{Path, PathBuf};
use crate::common::run;

/// A folder of the test's own: the tests run in parallel and write files of the same names.
fn dir(test: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("smoothlab-render-cli-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Width, height and the number of distinct colours of a PNG (read back with tiny-skia).
fn png_facts(path: &Path) -> (u32, u32, usize) {
    let pm = tiny_skia::Pixmap::load_png(path).unwrap();
    let mut colours: Vec<[u8; 4]> = pm.pixels().iter().map(|p| [p.red(), p.green(), p.blue(), p.alpha()]).collect();
    colours.sort_unstable();
    colours.dedup();
    (pm.width(), pm.height(), colours.len())
}

fn tangled_plate(d: &Path) -> String {
    let plate = d.join("plate.vtk");
    let tangled = d.join("tangled.vtk");
    assert!(run(&["generate", "plate", "--kind", "tri", "-o", plate.to_str().unwrap()]).status.success());
    let out = run(&["generate", "perturb", plate.to_str().unwrap(), "--amount", "0.5", "--seed", "1", "-o", tangled.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    tangled.to_str().unwrap().to_string()
}

#[test]
fn every_view_draws_a_picture_of_the_asked_size() {
    let d = dir("views");
    let mesh = tangled_plate(&d);
    let m = smoothlab::io::read_path(Path::new(&mesh)).unwrap();
    let free = (0..m.node_count()).rev().find(|&n| m.is_free(n)).unwrap().to_string();
    for (view, extra) in [
        ("mesh", vec!["--metric", "angle"]),
        ("mesh", vec!["--metric", "condition", "--passes", "1", "--objective", "old"]),
        ("levelset", vec![]),
        ("levelset", vec!["--objective", "new"]),
        ("history", vec!["--passes", "2"]),
        ("history", vec!["--node", free.as_str()]),
        ("histogram", vec!["--passes", "1"]),
        ("compare", vec!["--passes", "1"]),
    ] {
        let out = d.join(format!("{view}.png"));
        let mut args = vec!["render", &mesh, "-o", out.to_str().unwrap(), "--view", view, "--size", "400x300"];
        args.extend(extra.iter().copied());
        let o = run(&args);
        assert!(o.status.success(), "{view} {extra:?}: {}", String::from_utf8_lossy(&o.stderr));
        let (w, h, colours) = png_facts(&out);
        assert_eq!((w, h), (400, 300), "{view} {extra:?}");
        assert!(colours > 20, "{view} {extra:?}: only {colours} colours — blank?");
    }
    // device-pixel ratio 2 doubles the pixels
    let out = d.join("dpr2.png");
    let o = run(&["render", &mesh, "-o", out.to_str().unwrap(), "--view", "mesh", "--size", "200x150", "--dpr", "2"]);
    assert!(o.status.success());
    assert_eq!(png_facts(&out).0, 400);
}

#[test]
fn bad_requests_are_refused_with_a_message() {
    let d = dir("refusals");
    let mesh = tangled_plate(&d);
    let out = d.join("x.png");
    let o = out.to_str().unwrap();
    for (args, want) in [
        (vec!["--objective", "sine"], "--objective sine"),
        (vec!["--view", "levelset", "--node", "0"], "not a free corner node"),
        (vec!["--view", "levelset", "--node", "99999"], "the mesh has nodes 0 to"),
        (vec!["--size", "12by"], "WIDTHxHEIGHT"),
        (vec!["--size", "9000x10"], "give 1 to 4096"),
        (vec!["--view", "compare", "--objective", "new"], "both objectives"),
        (vec!["--dpr", "0"], "--dpr"),
        // issue 16: the mesh view drew a highlight for a node that does not exist
        (vec!["--view", "mesh", "--node", "99999"], "--node 99999: the mesh has nodes 0 to"),
        (vec!["--view", "histogram", "--node", "99999"], "--node 99999: the mesh has nodes 0 to"),
    ] {
        let mut all = vec!["render", mesh.as_str(), "-o", o];
        all.extend(args.iter().copied());
        let r = run(&all);
        assert!(!r.status.success(), "{args:?} must fail");
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

/// Over the million nodes the pictures take, the refusal is the command-line tool's own,
/// with the file's name (it was the page's "use the command-line tool"). Issue 16.
#[test]
fn a_mesh_over_the_render_limit_is_refused_in_this_tools_words() {
    let d = dir("too-many");
    let big = d.join("big.vtk");
    let o = run(&["generate", "grid", "--nx", "1001", "--ny", "1000", "-o", big.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = run(&["render", big.to_str().unwrap(), "-o", d.join("x.png").to_str().unwrap(), "--view", "mesh"]);
    assert!(!r.status.success());
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(err.contains("big.vtk") && err.contains("1003002 nodes") && err.contains("render draws meshes of at most 1000000"), "{err}");
    assert!(!err.contains("the page") && !err.contains("use the command-line tool"), "{err}");
    std::fs::remove_dir_all(&d).unwrap();
}

/// `--theme dark` draws the projector theme: the level sets of Chen's star configuration,
/// compared pixel for pixel with `tests/images/cli_levelset_dark.png`
/// (`UPDATE_GOLDEN=1` rewrites it). The default stays the light theme.
#[test]
fn the_dark_theme_draws_the_golden_picture() {
    let d = dir("dark");
    let star = d.join("star.vtk");
    let o = run(&["generate", "star", "--kind", "chen", "-o", star.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = d.join("dark.png");
    let args = ["render", star.to_str().unwrap(), "-o", out.to_str().unwrap(), "--view", "levelset", "--size", "760x420"];
    let o = run(&[&args[..], &["--theme", "dark"]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let got = tiny_skia::Pixmap::load_png(&out).unwrap();
    let golden = crate::common::repo().join("tests/images/cli_levelset_dark.png");
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        got.save_png(&golden).unwrap();
    }
    let want = tiny_skia::Pixmap::load_png(&golden).unwrap();
    assert_eq!((got.width(), got.height()), (want.width(), want.height()));
    let differ = got.pixels().iter().zip(want.pixels()).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "{differ} pixels differ from {}", golden.display());
    // the corner is the dark paper (#14171b); the light default's is white
    let c = got.pixel(1, 1).unwrap();
    assert_eq!((c.red(), c.green(), c.blue()), (20, 23, 27));
    let light = d.join("light.png");
    let o = run(&["render", star.to_str().unwrap(), "-o", light.to_str().unwrap(), "--view", "levelset", "--size", "760x420"]);
    assert!(o.status.success());
    let c = tiny_skia::Pixmap::load_png(&light).unwrap().pixel(1, 1).unwrap();
    assert_eq!((c.red(), c.green(), c.blue()), (255, 255, 255));
    let o = run(&[&args[..], &["--theme", "sepia"]].concat());
    assert!(!o.status.success());
    std::fs::remove_dir_all(&d).unwrap();
}
