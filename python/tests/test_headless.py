"""The headless front door, as pip installed it from the wheel, against the command-line
tool built from the same tree: a planar, a surface and a volume file read, smoothed with
the defaults and written give the tool's bytes; the statistics and the per-pass records
are its JSON; arrays in and out, meshio, pictures; the interpreter is free while smoothing."""

import importlib.metadata
import json
import os
import pathlib
import re
import subprocess
import threading
import time

import numpy as np
import pytest

import smoothlab
from conftest import ROOT

CLI = pathlib.Path(os.environ.get("SMOOTHLAB_CLI", ROOT / "target" / "debug" / "smoothlab"))


def cli(*args, cwd=None):
    if not os.access(CLI, os.X_OK):
        pytest.fail(f"the command-line tool is not built at {CLI} (cargo build -p smoothlab-cli)")
    done = subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True, cwd=cwd)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A planar Gmsh file of the site, a tangled surface of quads and triangles, and a
    bent, tangled block of hexahedra (the issue's three), made by the tool."""
    d = tmp_path_factory.mktemp("meshes")
    cli("generate", "torus", "--kind", "mixed", "-o", d / "torus.vtk")
    cli("generate", "perturb", d / "torus.vtk", "--amount", "0.4", "-o", d / "surface.vtk")
    cli("generate", "hexgrid", "--cells", "4", "--bend", "20", "-o", d / "hex.vtk")
    cli("generate", "perturb", d / "hex.vtk", "--amount", "0.3", "-o", d / "volume.msh")
    planar = d / "planar.msh"
    planar.write_bytes((ROOT / "www" / "samples" / "plate_hole_tri.msh").read_bytes())
    return {"planar": planar, "surface": d / "surface.vtk", "volume": d / "volume.msh"}


KINDS = ["planar", "surface", "volume"]
TIMES = {"time_ms", "elapsed_ms", "stats_ms"}


def untimed(x):
    """A report without its clock readings, which differ from run to run."""
    if isinstance(x, dict):
        return {k: untimed(v) for k, v in x.items() if k not in TIMES}
    if isinstance(x, list):
        return [untimed(v) for v in x]
    return x


def test_the_package_is_the_installed_wheel():
    installed = pathlib.Path(smoothlab.__file__).resolve()
    assert "site-packages" in installed.parts, f"{installed} is not the installed package"
    assert not installed.is_relative_to(ROOT / "python")
    assert smoothlab.__version__ == importlib.metadata.version("smoothlab")
    needs = [r for r in importlib.metadata.requires("smoothlab") if "extra ==" not in r]
    assert needs == ["numpy"], needs
    assert (installed.parent / "py.typed").is_file()
    # the widget's bridge, and the page it shows (gzipped, its wasm inside), packed apart
    assert 0 < (installed.parent / "static" / "widget.js").stat().st_size < 50_000
    assert (installed.parent / "static" / "page.html.gz").stat().st_size > 1_000_000


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("ext", ["vtk", "msh"])
def test_read_smooth_write_gives_the_tools_bytes(files, kind, ext, tmp_path):
    src = files[kind]
    out_cli, out_py = tmp_path / f"cli.{ext}", tmp_path / f"py.{ext}"
    printed = json.loads(cli("smooth", src, "-o", out_cli, "--json"))
    mesh = smoothlab.read(src)
    assert mesh.kind == kind
    report = mesh.smooth()
    smoothlab.write(mesh, out_py)
    assert out_py.read_bytes() == out_cli.read_bytes()
    assert untimed(report.as_dict()) == untimed(printed)
    assert report.passes and len(report.passes) == 3 + report.finish and report.inverted == printed["final"]["inverted"]


@pytest.mark.parametrize("kind", KINDS)
def test_stats_are_the_tools_json(files, kind):
    assert smoothlab.read(files[kind]).stats() == json.loads(cli("stats", files[kind], "--json"))


def test_numpy_numbers_are_settings(files):
    report = smoothlab.read(files["planar"]).smooth(passes=np.int64(2), strategy="c1", threshold=np.float64(20), finish=np.int64(0))
    assert len(report.passes) == 2


def test_settings_reach_the_core_as_the_tools_flags(files, tmp_path):
    flags = ["--strategy", "c2", "--threshold", "15", "--passes", "2", "--order", "priority", "--max-iter", "5",
             "--objective", "condition", "--no-pass-through-folds", "--finish", "1"]
    cli("smooth", files["planar"], "-o", tmp_path / "cli.vtk", *flags)
    mesh = smoothlab.read(files["planar"])
    report = mesh.smooth(strategy="c2", threshold=15, passes=2, order="priority", max_iter=5, objective="condition",
                         pass_through_folds=False, finish=1)
    smoothlab.write(mesh, tmp_path / "py.vtk")
    assert (tmp_path / "py.vtk").read_bytes() == (tmp_path / "cli.vtk").read_bytes()
    assert (report.objective, report.strategy, len(report.passes) - report.finish) == ("condition", "c2", 2)
    cli("smooth", files["surface"], "-o", tmp_path / "cli-s.msh", "--slide-curves", "--msh-version", "4.1")
    surface = smoothlab.read(files["surface"])
    surface.smooth(slide_curves=True)
    smoothlab.write(surface, tmp_path / "py-s.msh", msh_version="4.1")
    assert (tmp_path / "py-s.msh").read_bytes() == (tmp_path / "cli-s.msh").read_bytes()


@pytest.mark.parametrize("kind", KINDS)
def test_the_input_target_is_the_tools(files, kind, tmp_path):
    cli("smooth", files[kind], "-o", tmp_path / "cli.vtk", "--target", "input", "--strategy", "opt")
    mesh = smoothlab.read(files[kind])
    report = mesh.smooth(target="input", strategy="opt")
    smoothlab.write(mesh, tmp_path / "py.vtk")
    assert (tmp_path / "py.vtk").read_bytes() == (tmp_path / "cli.vtk").read_bytes()
    assert report.target == "input" and "input" in smoothlab.settings()["target"]
    with pytest.raises(ValueError, match="target"):
        mesh.smooth(target="input", strategy="laplace")


def test_sliding_boundaries_are_the_tools(files, tmp_path):
    cli("smooth", files["volume"], "-o", tmp_path / "cli.vtk", "--boundary", "slide", "--feature-angle", "40")
    mesh = smoothlab.read(files["volume"])
    report = mesh.smooth(boundary="slide", feature_angle=40)
    smoothlab.write(mesh, tmp_path / "py.vtk")
    assert (tmp_path / "py.vtk").read_bytes() == (tmp_path / "cli.vtk").read_bytes()
    # the bent block's eight corners hold; its twelve edges are feature curves
    b = report.boundary
    assert (b["corners"], b["curves"], b["feature_angle_deg"]) == (8, 12, 40.0), b
    assert b["max_distance"] < 1e-12 * b["mean_edge"], b
    assert "slide" in smoothlab.settings()["boundary"]
    assert smoothlab.read(files["volume"]).smooth().boundary is None
    # a surface's boundary is its open edges and feature curves: the torus has none
    cli("smooth", files["surface"], "-o", tmp_path / "cli-s.vtk", "--boundary", "slide")
    surface = smoothlab.read(files["surface"])
    assert surface.smooth(boundary="slide").boundary["curves"] == 0
    smoothlab.write(surface, tmp_path / "py-s.vtk")
    assert (tmp_path / "py-s.vtk").read_bytes() == (tmp_path / "cli-s.vtk").read_bytes()
    with pytest.raises(ValueError, match="feature_angle"):
        smoothlab.read(files["volume"]).smooth(feature_angle=40)


def test_the_settings_are_the_smooth_commands_flags():
    """Every option of `smoothlab smooth` that sets the run is a setting of Mesh.smooth."""
    help_text = cli("smooth", "--help")
    flags = set(re.findall(r"--([a-z][a-z-]*)", help_text))
    not_settings = {"output", "json", "msh-version", "help", "no-pass-through-folds"}
    assert {f.replace("-", "_") for f in flags - not_settings} == set(smoothlab.settings())


@pytest.mark.parametrize("kind", KINDS)
def test_arrays_out_and_back_in_are_the_same_mesh(files, kind, tmp_path):
    mesh = smoothlab.read(files[kind])
    points, cells = mesh
    assert points.dtype == np.float64 and points.shape == (mesh.stats()["nodes"], 2 if kind == "planar" else 3)
    assert not points.flags.writeable and mesh.fixed.dtype == bool and mesh.fixed.shape == (len(points),)
    again = smoothlab.Mesh(points, cells, mesh.fixed)
    smoothlab.write(mesh, tmp_path / "a.vtk")
    smoothlab.write(again, tmp_path / "b.vtk")
    assert (tmp_path / "a.vtk").read_bytes() == (tmp_path / "b.vtk").read_bytes()
    # smoothing moves the arrays seen afterwards, and a copy stays as it was
    before = mesh.copy()
    mesh.smooth(passes=1)
    assert not np.array_equal(mesh.points, before.points) and np.array_equal(before.points, points)


def test_meshio_in_and_out(files, tmp_path):
    meshio = pytest.importorskip("meshio", reason="meshio is optional for the package, installed by make test")
    mesh = smoothlab.read(files["volume"])
    m = mesh.to_meshio()
    assert [b.type for b in m.cells][0] == "hexahedron" and m.point_data["fixed"].sum() == mesh.fixed.sum()
    m.write(tmp_path / "via-meshio.vtk")
    back = smoothlab.Mesh.from_meshio(meshio.read(tmp_path / "via-meshio.vtk"))
    assert back.kind == "volume" and np.array_equal(back.fixed, mesh.fixed) and np.array_equal(back.points, mesh.points)
    with pytest.raises(ValueError, match="mesh: from_meshio takes a meshio.Mesh, not ndarray"):
        smoothlab.Mesh.from_meshio(mesh.points)


def test_a_mesh_given_in_3d_at_z_0_comes_back_in_3d():
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.8, 0.7, 0]], dtype=float)
    mesh = smoothlab.Mesh(points, np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))
    assert mesh.kind == "planar" and mesh.points.shape == (5, 3)
    mesh.smooth()
    assert np.all(mesh.points[:, 2] == 0) and np.allclose(mesh.points[4, :2], [0.5, 0.5], atol=1e-3)


RENDERS = [
    # (kind, the tool's options, the same as Python's arguments)
    ("planar", [], {}),
    ("planar", ["--view", "mesh", "--metric", "angle", "--node", "40", "--theme", "dark"], {"metric": "angle", "node": 40, "theme": "dark"}),
    ("planar", ["--view", "compare", "--passes", "1", "--size", "700x400"], {"view": "compare", "passes": 1, "size": (700, 400)}),
    ("planar", ["--view", "levelset", "--objective", "new", "--strategy", "opt"], {"view": "levelset", "objective": "new", "strategy": "opt"}),
    ("planar", ["--view", "history", "--passes", "2", "--order", "input", "--max-iter", "4"], {"view": "history", "passes": 2, "order": "input", "max_iter": 4}),
    ("planar", ["--view", "histogram", "--passes", "1", "--strategy", "c1", "--threshold", "15"], {"view": "histogram", "passes": 1, "strategy": "c1", "threshold": 15}),
    ("surface", ["--view", "mesh", "--camera", "40,20,1.2", "--dpr", "2", "--size", "300x200"], {"camera": (40, 20, 1.2), "dpr": 2, "size": (300, 200)}),
    ("surface", ["--view", "compare", "--passes", "1", "--penalty", "angle"], {"view": "compare", "passes": 1, "penalty": "angle"}),
    ("surface", ["--view", "levelset"], {"view": "levelset"}),
    ("volume", ["--view", "mesh", "--cut", "x=0.4"], {"cut": ("x", 0.4)}),
    ("volume", ["--view", "compare", "--passes", "1", "--cut", "y=0.5"], {"view": "compare", "passes": 1, "cut": "y=0.5"}),
    ("volume", ["--view", "histogram", "--passes", "1"], {"view": "histogram", "passes": 1}),
]


@pytest.mark.parametrize("kind, flags, kwargs", RENDERS)
def test_render_draws_the_tools_pictures(files, kind, flags, kwargs, tmp_path):
    args = flags if "--view" in flags else ["--view", "mesh", *flags]
    cli("render", files[kind], "-o", tmp_path / "cli.png", *args)
    smoothlab.render(smoothlab.read(files[kind]), tmp_path / "py.png", **kwargs)
    png = (tmp_path / "py.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and png == (tmp_path / "cli.png").read_bytes()


def test_render_draws_the_mesh_as_it_is_now(files, tmp_path):
    mesh = smoothlab.read(files["surface"])
    smoothlab.render(mesh, tmp_path / "before.png", size=(300, 200), dpr=2)
    png = (tmp_path / "before.png").read_bytes()
    assert int.from_bytes(png[16:20], "big") == 600 and int.from_bytes(png[20:24], "big") == 400
    mesh.smooth(passes=1)
    smoothlab.render(mesh, tmp_path / "after.png", size=(300, 200), dpr=2)
    assert (tmp_path / "after.png").read_bytes() != png


def test_smoothing_lets_other_threads_run(tmp_path):
    cli("generate", "rand2d", "--points", "30000", "-o", tmp_path / "big.vtk")
    mesh = smoothlab.read(tmp_path / "big.vtk")
    result = {}
    worker = threading.Thread(target=lambda: result.setdefault("report", mesh.smooth(passes=3)))
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    took = result["report"].time_ms / 1000
    gaps = np.diff(ticks)
    assert took > 0.1, f"the run took {took:.3f} s: too short to tell"
    # held, the interpreter would stop this loop for the whole run
    assert gaps.max() < took / 2, f"this thread stood still {gaps.max():.3f} s of a {took:.3f} s run"


BAD_SETTINGS = [
    ({"passes": 0}, r"^passes: 0 asked: give 1 to 10000$"),
    ({"passes": -2}, r"^passes: -2 asked: give a positive whole number$"),
    ({"passes": True}, r"^passes: give a whole number, not True$"),
    ({"passes": 2.5}, r"^passes: give a whole number, not 2.5$"),
    ({"passes": 2.0}, r"^passes: give a whole number, not 2.0$"),
    ({"strategy": "best"}, r"^strategy: \"best\" is not one of laplace, smart, opt, c1, c2, c3, rules$"),
    ({"objective": 3}, r"^objective: give a name \(old, sine, new, .*\), not 3$"),
    ({"threshold": 20}, r"^threshold: c1, c2 and c3 have one, not rules$"),
    ({"strategy": "c1", "threshold": 95}, r"^threshold: 95 asked: give degrees above 0 and at most 90$"),
    ({"strategy": "laplace", "max_iter": 3}, r"^max_iter: laplace never calls the solver$"),
    ({"objective": "old", "penalty": "angle"}, r"^penalty: it is a design of the new objective$"),
    ({"pass_through_folds": "yes"}, r"^pass_through_folds: give True or False, not 'yes'$"),
    ({"speed": 3}, r"^no setting named \"speed\": the settings are objective, strategy, threshold, passes, order"),
    ({"slide_curves": True}, r"^slide_curves: a surface's curves slide; this mesh is planar$"),
]


@pytest.mark.parametrize("settings, words", BAD_SETTINGS)
def test_bad_settings_are_refused_naming_them(files, settings, words):
    mesh = smoothlab.read(files["planar"])
    before = mesh.points.copy()
    with pytest.raises(ValueError, match=words):
        mesh.smooth(**settings)
    assert np.array_equal(mesh.points, before)


def test_bad_files_name_the_file_and_the_line(tmp_path):
    bad = tmp_path / "bad.vtk"
    bad.write_text("# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 0\n1 0 0\n0 1 zero\n")
    with pytest.raises(ValueError, match=r"bad\.vtk: line 8: "):
        smoothlab.read(bad)
    with pytest.raises(ValueError, match=r"cannot tell the mesh format of '.*mesh\.txt'"):
        smoothlab.read(tmp_path / "mesh.txt")
    with pytest.raises(OSError, match=r"cannot read .*missing\.vtk"):
        smoothlab.read(tmp_path / "missing.vtk")
    mesh = smoothlab.Mesh([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]])
    with pytest.raises(ValueError, match=r"cannot tell the mesh format of '.*out\.png'"):
        smoothlab.write(mesh, tmp_path / "out.png")
    with pytest.raises(ValueError, match=r"msh_version: \"3\" is not one of 2.2, 4.1"):
        smoothlab.write(mesh, tmp_path / "out.msh", msh_version="3")
    with pytest.raises(ValueError, match=r"mesh: give a smoothlab.Mesh"):
        smoothlab.write(mesh.points, tmp_path / "out.vtk")


def test_bad_pictures_are_refused_naming_the_argument(files, tmp_path):
    planar, surface, volume = (smoothlab.read(files[k]) for k in KINDS)
    out = tmp_path / "p.png"
    cases = [
        (planar, {"view": "sketch"}, r"^view: \"sketch\" is not one of mesh, levelset, history, histogram, compare$"),
        (planar, {"size": (0, 10)}, r"a picture of 0 × 10 pixels"),
        (planar, {"size": 300}, r"^size: give \(width, height\) in pixels, not 300$"),
        (planar, {"dpr": 0}, r"^dpr 0: give a ratio above 0 and at most 4$"),
        (planar, {"camera": (1, 2)}, r"^camera turns the 3D view of a surface; this mesh is planar$"),
        (planar, {"camera": ("a", 2)}, r"^camera: give \(yaw, pitch\) or \(yaw, pitch, zoom\) in numbers"),
        (planar, {"cut": "z=0.5"}, r"^cut cuts a volume mesh; this mesh is planar$"),
        (planar, {"metric": "beauty"}, r"^metric: \"beauty\" is not one of alpha, angle, condition$"),
        (planar, {"node": 100000}, r"^node 100000: the mesh has nodes 0 to 589$"),
        (planar, {"passes": 5000}, r"^passes 5000: give at most 1000$"),
        (planar, {"objective": "best"}, r"^objective best: the pictures compare the old max-min objective and the new"),
        (planar, {"view": "compare", "objective": "new"}, r"^view compare shows both objectives: use objective old,new$"),
        (planar, {"theme": "blue"}, r"^theme: give \"light\" or \"dark\", not \"blue\"$"),
        (surface, {"cut": ("z", 0.5)}, r"^cut: it cuts a volume mesh; this mesh is a surface$"),
        (surface, {"view": "histogram"}, r"^view histogram: a surface is drawn by view mesh, compare or levelset$"),
        (volume, {"cut": ("w", 0.5)}, r"^cut: "),
        (volume, {"cut": "z"}, r"^cut: "),
        (volume, {"metric": "angle"}, r"^metric: a volume mesh's cut is coloured by the mean ratio$"),
        (volume, {"view": "levelset"}, r"^view levelset: a volume mesh is drawn by view mesh, compare or histogram$"),
    ]
    for mesh, kwargs, words in cases:
        with pytest.raises(ValueError, match=words):
            smoothlab.render(mesh, out, **kwargs)
    assert not out.exists()
