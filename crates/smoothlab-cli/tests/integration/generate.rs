//! The `generate` subcommand end to end (write, read back, check), and the sample meshes
//! of `www/samples/` made by Gmsh.

use std::path::{Path, PathBuf};
use std::process::Command;

use smoothlab::io::read_path;
use smoothlab::quality::mesh_stats;
use smoothlab::Mesh;

fn out(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("generate");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Runs `smoothlab generate ARGS`, returning (success, stderr).
fn generate(args: &[&str]) -> (bool, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_smoothlab")).arg("generate").args(args).output().unwrap();
    (o.status.success(), String::from_utf8_lossy(&o.stderr).into_owned())
}

fn generated(args: &[&str], file: &str) -> Mesh {
    let path = out(file);
    let mut all: Vec<&str> = args.to_vec();
    let p = path.to_str().unwrap();
    all.extend(["-o", p]);
    let (ok, err) = generate(&all);
    assert!(ok, "smoothlab generate {args:?} failed: {err}");
    let m = read_path(&path).unwrap();
    m.sanity_check().unwrap();
    m
}

#[test]
fn rand2d_default_is_freitags_mesh() {
    let m = generated(&["rand2d"], "rand2d.msh");
    let s = mesh_stats(&m);
    assert_eq!((s.nodes, s.elements, s.free_nodes, s.inverted), (580, 1078, 500, 0));
}

#[test]
fn the_seed_names_the_mesh() {
    let _ = generated(&["rand2d", "--points", "50", "--per-side", "5", "--seed", "7"], "a.msh");
    let _ = generated(&["rand2d", "--points", "50", "--per-side", "5", "--seed", "7"], "b.msh");
    let _ = generated(&["rand2d", "--points", "50", "--per-side", "5", "--seed", "8"], "c.msh");
    let read = |f: &str| std::fs::read(out(f)).unwrap();
    assert_eq!(read("a.msh"), read("b.msh"));
    assert_ne!(read("a.msh"), read("c.msh"));
}

#[test]
fn grid_plate_and_star_counts() {
    let g = generated(&["grid", "--nx", "3", "--ny", "2", "--kind", "quad"], "grid.vtk");
    assert_eq!((g.node_count(), g.element_count(), g.free_count()), (12, 6, 2));
    let p = generated(&["plate", "--kind", "mixed", "--order", "2", "--resolution", "2"], "plate.msh");
    let s = mesh_stats(&p);
    // m = 16 spokes, 4 rings: 2 of quads, 2 of triangles; 80 corners + 176 mid nodes
    assert_eq!((s.quads, s.triangles, s.quadratic, s.nodes, s.inverted), (32, 64, 96, 256, 0));
    let curved: Vec<_> = p.edges().iter().filter(|e| e.curved).collect();
    assert_eq!(curved.len(), 16);
    for e in curved {
        assert!((p.nodes()[e.mid as usize].length() - 0.4).abs() < 1e-12);
    }
    for (kind, k, nodes) in [("regular", None, 7), ("chen", None, 9), ("quad", None, 9), ("quad", Some("6"), 13)] {
        let mut args = vec!["star", "--kind", kind];
        if let Some(k) = k {
            args.extend(["--k", k]);
        }
        let m = generated(&args, &format!("star-{kind}-{nodes}.vtk"));
        assert_eq!((m.node_count(), m.free_count()), (nodes, 1), "{kind}");
        assert_eq!(mesh_stats(&m).inverted, 0);
    }
}

#[test]
fn perturb_tangles_and_keeps_the_boundary() {
    let src = generated(&["plate", "--kind", "tri", "--resolution", "3"], "plate-tri.msh");
    let input = out("plate-tri.msh");
    let t = generated(&["perturb", input.to_str().unwrap(), "--amount", "1.0", "--seed", "2"], "tangled.msh");
    assert!(mesh_stats(&t).inverted > 0);
    let r = src.mean_edge_length();
    for n in 0..src.node_count() {
        let d = src.nodes()[n].distance(t.nodes()[n]);
        if src.fixed()[n] {
            assert!(d < 1e-12, "fixed node {n} moved");
        } else {
            assert!(d <= r * (1.0 + 1e-9), "node {n} moved {d} > {r}");
        }
    }
}

#[test]
fn bad_requests_say_what_is_wrong() {
    let o = out("never.msh");
    let o = o.to_str().unwrap();
    let (ok, err) = generate(&["star", "--kind", "chen", "--k", "7", "-o", o]);
    assert!(!ok && err.contains("even number"), "{err}");
    let (ok, err) = generate(&["plate", "--order", "3", "-o", o]);
    assert!(!ok && err.contains("order"), "{err}");
    let (ok, err) = generate(&["perturb", "no-such-mesh.msh", "-o", o]);
    assert!(!ok && err.contains("no-such-mesh.msh"), "{err}");
    let (ok, err) = generate(&["grid", "--nx", "0", "-o", o]);
    assert!(!ok && err.contains("at least one cell"), "{err}");
    assert!(!Path::new(o).exists());
}

fn sample(name: &str) -> Mesh {
    let path = crate::common::repo().join("www/samples").join(name);
    let m = read_path(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
    m.sanity_check().unwrap();
    assert_eq!(mesh_stats(&m).inverted, 0, "{name}");
    for n in 0..m.node_count() {
        assert!(!m.is_boundary(n) || m.fixed()[n], "{name}: boundary node {n} is free");
    }
    m
}

#[test]
fn gmsh_samples_load_valid() {
    let p = sample("plate_hole_tri.msh");
    assert!(p.kinds().iter().all(|k| *k == smoothlab::ElementKind::Tri3) && p.element_count() > 500);
    let b = sample("bracket_quad.msh");
    assert!(b.has_quads() && !b.has_quadratic());
    let d = sample("disk_tri6.msh");
    assert!(d.kinds().iter().all(|k| *k == smoothlab::ElementKind::Tri6));
    // every boundary edge is curved, its mid node on the circle or on the ellipse
    let (sa, sb, turn) = (0.45f64, 0.25f64, 30f64.to_radians());
    let mut boundary = 0;
    for e in d.edges().iter().filter(|e| e.is_boundary()) {
        boundary += 1;
        assert!(e.curved, "boundary edge {e:?}");
        let q = d.nodes()[e.mid as usize];
        let on_circle = (q.length() - 1.0).abs() < 1e-9;
        let l = q - glam::DVec2::new(0.1, 0.05);
        let (u, v) = (l.x * turn.cos() + l.y * turn.sin(), -l.x * turn.sin() + l.y * turn.cos());
        let on_ellipse = ((u / sa).powi(2) + (v / sb).powi(2) - 1.0).abs() < 1e-6;
        assert!(on_circle || on_ellipse, "mid node {q}");
    }
    assert!(boundary > 40);
}
