"""The README's notebook cells (its "Jupyter" part) run as written, in order, with the
package as pip installed it: a Gmsh file of the site read by meshio, shown, read back."""

import re
import shutil

import numpy as np
import pytest

from conftest import ROOT


def notebook_cells():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    part = text[text.index("**Jupyter**") : text.index("## The command-line tool")]
    cells = re.findall(r"```python\n(.*?)```", part, flags=re.S)
    assert len(cells) >= 2, "the README's Jupyter part has lost its notebook cells"
    return cells


def test_the_readmes_notebook_cells_run(tmp_path, monkeypatch):
    pytest.importorskip("meshio", reason="the README's cells read a file with meshio")
    shutil.copy(ROOT / "www" / "samples" / "plate_hole_tri.msh", tmp_path)
    monkeypatch.chdir(tmp_path)
    scope = {}
    for cell in notebook_cells():
        exec(compile(cell, "README.md", "exec"), scope)
    w, points, cells = scope["w"], scope["points"], scope["cells"]
    assert w.passes == 3 and points.shape[1] == 3 and cells[0][1].ndim == 2
    import meshio

    written = meshio.read(tmp_path / "plate-smoothed.vtk")
    assert np.array_equal(written.points, points)
