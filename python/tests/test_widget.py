"""The widget's arguments and traits, checked against the page's own sheet (the wasm
module's control sheet, samples and figures, written by make python)."""

import base64
import gzip
import json

import numpy as np
import pytest
import traitlets

import smoothlab
import smoothlab.widget
from smoothlab.widget import SHEET


def test_samples_and_figures_are_the_pages():
    assert "plate-tri-tangled" in smoothlab.samples() and "rand3d" in smoothlab.samples()
    assert "chen-10" in smoothlab.figures() and len(smoothlab.figures()) >= 14
    assert smoothlab.Playground(sample="plate-tri-tangled").sample == "plate-tri-tangled"
    assert smoothlab.Playground(figure="chen-10").figure == "chen-10"


def test_an_unknown_sample_or_figure_lists_the_names():
    with pytest.raises(ValueError, match=r"no sample named 'plate'; the samples are plate-quad-tangled-hard, plate-quad-tangled, plate-tri-tangled, .*rand3d"):
        smoothlab.Playground(sample="plate")
    with pytest.raises(ValueError, match=r"no figure named 'chen-99'; the figures are chen-2, "):
        smoothlab.Playground(figure="chen-99")


def test_a_sample_has_no_arrays_until_the_page_reports():
    w = smoothlab.Playground(sample="rand2d")
    with pytest.raises(RuntimeError, match="side A's mesh is made by the page: show the widget"):
        w.mesh_a


def test_settings_are_checked_against_the_control_sheet(square):
    points, cells = square
    w = smoothlab.Playground(points, cells, strategy="c1", passes=5, objective_a="condition", threshold=15)
    assert (w.strategy, w.passes, w.objective_a, w.threshold) == ("c1", 5, "condition", 15)
    assert w.order is None  # the page's default, filled in once shown
    with pytest.raises(traitlets.TraitError, match=r"strategy: 'best' is not offered; choose one of laplace, smart, opt"):
        w.strategy = "best"
    with pytest.raises(traitlets.TraitError, match=r"objective_b: 'newest' is not offered"):
        w.objective_b = "newest"
    top = int(SHEET["controls"]["passes"]["max"])
    with pytest.raises(traitlets.TraitError, match=rf"passes: {top + 1} is out of range; Passes: "):
        w.passes = top + 1
    with pytest.raises(TypeError, match="no setting named 'speed'"):
        smoothlab.Playground(points, cells, speed=3)


def test_the_widget_module_shows_the_page_every_widget_shares(square):
    """The module is the bridge alone; the page (3 MB, its wasm inside) is the state of one
    model that every widget of the kernel refers to, so a notebook saved with its widgets'
    state holds it once."""
    module = smoothlab.widget.MODULE.read_text(encoding="utf-8")
    assert module.startswith("// written by scripts/single.mjs")
    assert "export default { render }" in module and "data-host" in module and "widget_manager" in module
    assert len(module) < 50_000
    points, cells = square
    ws = [smoothlab.Playground(points, cells), smoothlab.Playground(sample="rand2d"), smoothlab.Playground(figure="chen-10")]
    assert ws[0]._page is ws[1]._page is ws[2]._page
    page = gzip.decompress(base64.b64decode(ws[0]._page.page)).decode("utf-8")
    assert page.startswith("<!doctype html>") and '<html lang="en">' in page and "worker-source" in page
    for w in ws:
        state = w.get_state()
        assert state["_page"] == f"IPY_MODEL_{ws[0]._page.model_id}" and "page" not in state
        assert len(json.dumps({k: v for k, v in state.items() if not isinstance(v, (bytes, memoryview))}, default=str)) < 100_000
    # a closed page model is made again for the next widget
    ws[0]._page.close()
    assert smoothlab.Playground(sample="rand2d")._page.comm is not None


def test_save_png_draws_a_side_as_render_does(square, tmp_path):
    points, cells = square
    w = smoothlab.Playground(points, cells)
    w.save_png(tmp_path / "b.png", size=(200, 160))
    smoothlab.render(w.mesh_b, tmp_path / "render.png", "mesh", size=(200, 160))
    assert (tmp_path / "b.png").read_bytes() == (tmp_path / "render.png").read_bytes()
    moved = smoothlab.Mesh(points + [[0, 0], [0, 0], [0, 0], [0, 0], [0.2, -0.1]], cells)
    w.set_state({"_mesh_a": {"dim": 2, "points": memoryview(moved.points.astype("<f8").tobytes()), "fixed": memoryview(moved.fixed.astype(np.uint8).tobytes()),
                             "cells": [{"vtk_type": 5, "per_cell": 3, "nodes": memoryview(cells.astype("<u4").tobytes())}]}})
    w.save_png(tmp_path / "a.png", "a", size=(200, 160))
    assert (tmp_path / "a.png").read_bytes() != (tmp_path / "b.png").read_bytes()
    with pytest.raises(ValueError, match=r"side: 'a' or 'b', not 'c'"):
        w.save_png(tmp_path / "c.png", "c")
    assert not (tmp_path / "c.png").exists()


def test_sample_figure_and_mesh_assigned_later_replace_what_was_shown(square):
    points, cells = square
    w = smoothlab.Playground(points, cells)
    w.set_state({"_mesh_b": {"dim": 2, "points": b"", "fixed": b"", "cells": []}, "stats": {"b": {"passes": 1}}})
    w.sample = "rand2d"
    assert (w.sample, w.figure, w._file, w._mesh_a, w._mesh_b, w.stats) == ("rand2d", None, b"", {}, {}, {})
    with pytest.raises(RuntimeError, match="side A's mesh is made by the page"):
        w.mesh_a  # the mesh given as arrays is no longer what is shown
    w.figure = "chen-10"
    assert (w.sample, w.figure) == (None, "chen-10")
    with pytest.raises(traitlets.TraitError, match=r"sample: no sample named 'plate'; the samples are plate-quad-tangled"):
        w.sample = "plate"
    assert w.figure == "chen-10"
    w.set_mesh(points, cells, fixed=[0, 1])
    assert (w.sample, w.figure) == (None, None) and w._file.startswith(b"# vtk")
    assert np.array_equal(w.mesh_b.points, points) and w.mesh_b.fixed.tolist() == [True, True, False, False, False]
    with pytest.raises(ValueError, match=r"cells\[0\] refers to point 9"):
        w.set_mesh(points, [[0, 1, 9]])
    assert w.mesh_b.fixed.tolist() == [True, True, False, False, False]  # a refused mesh leaves it


def test_a_side_as_the_page_sends_it_reads_back_through_the_core(square):
    """The page's arrays (www/app/host.js: little-endian f64 points, u32 nodes, u8 flags, as
    memoryviews from the kernel) become the side's Mesh, the same mesh again."""
    points, cells = square
    sent = smoothlab.Mesh(points + 0.125, cells, fixed=[0, 1, 2, 3])
    state = {
        "dim": 2,
        "points": memoryview(sent.points.astype("<f8").tobytes()),
        "cells": [{"vtk_type": 5, "per_cell": 3, "nodes": memoryview(sent.cells[0][1].astype("<u4").tobytes())}],
        "fixed": memoryview(sent.fixed.astype(np.uint8).tobytes()),
    }
    w = smoothlab.Playground(points, cells)
    w.set_state({"_mesh_b": state})
    b = w.mesh_b
    assert np.array_equal(b.points, sent.points) and np.array_equal(b.cells[0][1], cells)
    assert b.fixed.tolist() == [True, True, True, True, False] and b.stats() == sent.stats()
    # points given in 3D come back in 3D
    w3 = smoothlab.Playground(np.column_stack([points, np.zeros(5)]), cells)
    w3.set_state({"_mesh_b": state})
    assert w3.mesh_b.points.shape == (5, 3)


def test_the_view_is_checked_and_let_go_with_the_mesh(square):
    w = smoothlab.Playground(sample="hex-tangled", camera=(60, 10), cut=("x", 0.3))
    assert (w.camera, w.cut) == ([60.0, 10.0, 1.0], ["x", 0.3])
    with pytest.raises(traitlets.TraitError, match=r"camera: give \(yaw, pitch\) or \(yaw, pitch, zoom\) in finite numbers, not \[1, nan\]"):
        w.camera = [1, float("nan")]
    with pytest.raises(traitlets.TraitError, match=r"camera: the zoom -1.0 is not positive"):
        w.camera = (0, 0, -1)
    with pytest.raises(traitlets.TraitError, match=r"cut: the axis is 'x', 'y' or 'z', not 'w'"):
        w.cut = ("w", 0.5)
    with pytest.raises(traitlets.TraitError, match=r"cut: the fraction 1.5 is not between 0 and 1"):
        w.cut = ("z", 1.5)
    with pytest.raises(traitlets.TraitError, match=r"cut: give \(axis, fraction\) such as \('z', 0.5\), not 'z'"):
        smoothlab.Playground(sample="hex-tangled", cut="z")
    assert (w.camera, w.cut) == ([60.0, 10.0, 1.0], ["x", 0.3])  # a refused view leaves it
    w.sample = "rand3d"
    assert (w.camera, w.cut) == (None, None)


def test_save_png_sees_a_volume_by_the_widgets_view(tmp_path):
    # a 2 x 2 x 2 block of hexahedra, its middle node moved
    idx = lambda i, j, k: i + 3 * j + 9 * k
    points = np.array([[i, j, k] for k in range(3) for j in range(3) for i in range(3)], dtype=float)
    points[idx(1, 1, 1)] += [0.3, -0.2, 0.1]
    hexes = [[idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k), idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)]
             for k in range(2) for j in range(2) for i in range(2)]
    mesh = smoothlab.Mesh(points, [("hexahedron", np.array(hexes))])
    w = smoothlab.Playground(mesh.points, mesh.cells, camera=(70, 35, 1.2), cut=("y", 0.6))
    w.save_png(tmp_path / "w.png", size=(240, 200))
    smoothlab.render(w.mesh_b, tmp_path / "r.png", "mesh", size=(240, 200), camera=(70, 35, 1.2), cut=("y", 0.6))
    smoothlab.render(w.mesh_b, tmp_path / "default.png", "mesh", size=(240, 200))
    assert (tmp_path / "w.png").read_bytes() == (tmp_path / "r.png").read_bytes() != (tmp_path / "default.png").read_bytes()


def test_the_kernel_sends_the_page_when_the_view_asks(square):
    """A front end whose models cannot reach the shared page model asks by a message."""
    points, cells = square
    w = smoothlab.Playground(points, cells)
    sent = []
    w.send = lambda content, buffers=None: sent.append(content)
    w._on_message(w, {"smoothlab": "other"}, [])
    assert sent == []
    w._on_message(w, {"smoothlab": "page?"}, [])
    assert sent == [{"smoothlab": "page", "page": w._page.page}] and len(sent[0]["page"]) > 1_000_000
