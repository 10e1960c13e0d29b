"""Arrays out: what the page set on the model in the browser test (tests/browser/suites/
widget.mjs, which runs before these in make test and writes test-output/widget/state.json)
read through the package as a kernel receives it (binary buffers as memoryviews)."""

import base64
import json
import os

import numpy as np
import pytest

import smoothlab
from conftest import ROOT

STATE = ROOT / "test-output" / "widget" / "state.json"


def page_state():
    if not STATE.is_file():
        if os.environ.get("SMOOTHLAB_NEED_PAGE_STATE"):
            pytest.fail(f"{STATE} is missing: the widget's browser test writes it (make browser)")
        pytest.skip("the widget's browser test has not run (make browser writes the page's state)")
    raw = json.loads(STATE.read_text())

    def side(s):
        b = lambda t: memoryview(base64.b64decode(t))
        return {"dim": s["dim"], "points": b(s["points"]), "fixed": b(s["fixed"]),
                "cells": [{**c, "nodes": b(c["nodes"])} for c in s["cells"]]}

    return raw, {"_mesh_a": side(raw["_mesh_a"]), "_mesh_b": side(raw["_mesh_b"])}


def test_the_smoothed_meshes_come_back_as_arrays():
    raw, state = page_state()
    # the grid the browser test gave: 9 × 9 points, 8 × 8 quads
    points = np.array([[i, j] for j in range(9) for i in range(9)], dtype=float)
    cells = np.array([[j * 9 + i, j * 9 + i + 1, j * 9 + i + 10, j * 9 + i + 9] for j in range(8) for i in range(8)])
    w = smoothlab.Playground(points, cells)
    w.set_state(state)  # as the kernel's comm hands the frontend's update over
    a, b = w.mesh_a, w.mesh_b
    assert a.points.shape == b.points.shape == (81, 2) and a.points.dtype == np.float64
    assert [k for k, _ in b.cells] == ["quad"] and np.array_equal(b.cells[0][1], cells)
    assert b.fixed.sum() == 32 and not b.fixed[10]  # the boundary fixed, the inside free
    assert not np.array_equal(a.points, b.points)  # the two objectives moved them differently
    assert np.array_equal(b.points[b.fixed], points[b.fixed])  # the boundary stayed
    assert raw["stats"]["b"]["passes"] == 1
    assert "32 fixed" not in repr(b) and repr(b) == "Mesh(81 points in 2D; 64 quad)"


def test_points_given_in_3d_come_back_in_3d():
    _, state = page_state()
    points = np.array([[i, j, 0.0] for j in range(9) for i in range(9)])
    cells = np.array([[j * 9 + i, j * 9 + i + 1, j * 9 + i + 10, j * 9 + i + 9] for j in range(8) for i in range(8)])
    w = smoothlab.Playground(points, cells)
    w.set_state(state)
    got = w.mesh_b.points
    assert got.shape == (81, 3) and np.all(got[:, 2] == 0)
    flat = smoothlab.Playground(points[:, :2], cells)
    flat.set_state(state)
    assert np.array_equal(flat.mesh_b.points, got[:, :2])
