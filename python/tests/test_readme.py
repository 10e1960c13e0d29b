"""The notebook cells of the docs run as written, in order, with the package as pip
installed it: a Gmsh file of the site read by meshio, shown, read back. The cells are
docs/python.md's and the README's "From Python" example."""

import re
import shutil

import numpy as np
import pytest

from conftest import ROOT


def cells_of(path, start=None, end=None):
    """The ```python blocks of `path`, between the `start` and `end` texts if given."""
    text = (ROOT / path).read_text(encoding="utf-8")
    part = text[text.index(start) if start else 0 : text.index(end) if end else len(text)]
    return re.findall(r"```python\n(.*?)```", part, flags=re.S)


def notebook_cells():
    cells = cells_of("docs/python.md", "## A first cell", "## A mesh as arrays")
    assert len(cells) >= 2, "docs/python.md's first cell has gone"
    return cells


def readme_cells():
    cells = cells_of("README.md", "## From Python", "## Which guide to read")
    assert len(cells) == 1, "the README's Python example has gone"
    return cells


def test_the_readmes_notebook_cells_run(tmp_path, monkeypatch):
    pytest.importorskip("meshio", reason="the README's cells read a file with meshio")
    shutil.copy(ROOT / "www" / "samples" / "plate_hole_tri.msh", tmp_path)
    monkeypatch.chdir(tmp_path)
    scope = {}
    for cell in notebook_cells():
        exec(compile(cell, "docs/python.md", "exec"), scope)
    w, points, cells = scope["w"], scope["points"], scope["cells"]
    assert w.passes == 3 and points.shape[1] == 3 and cells[0][1].ndim == 2
    import meshio

    written = meshio.read(tmp_path / "plate-smoothed.vtk")
    assert np.array_equal(written.points, points)


def test_the_readmes_python_example_runs(tmp_path, monkeypatch):
    import smoothlab

    shutil.copy(ROOT / "www" / "samples" / "plate_hole_tri.msh", tmp_path)
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(readme_cells()[0], "README.md", "exec"), scope)
    assert scope["report"].inverted == 0
    back = smoothlab.read(tmp_path / "plate-smoothed.vtk")
    assert np.array_equal(back.points, scope["mesh"].points)
