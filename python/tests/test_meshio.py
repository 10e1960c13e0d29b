"""meshio in and out: a Gmsh file of the site read by meshio, and a side's mesh written
by meshio after the page has smoothed it."""

import numpy as np
import pytest

import smoothlab

meshio = pytest.importorskip("meshio", reason="meshio is optional for the package, installed by make test")

from conftest import ROOT, sections


def test_from_meshio_a_gmsh_file():
    mesh = meshio.read(ROOT / "www" / "samples" / "plate_hole_tri.msh")
    w = smoothlab.Playground.from_meshio(mesh)
    points, _, types, _ = sections(w._file.decode())
    assert np.array_equal(points, mesh.points)
    assert types == [code for b in mesh.cells for code in [{"triangle": 5, "line": 3, "vertex": 1}[b.type]] * len(b.data)]
    points, cells = w.mesh_a
    assert points.shape == mesh.points.shape and [k for k, _ in cells] == [b.type for b in mesh.cells]


def test_from_meshio_keeps_smoothlabs_fixed_flags(tmp_path, square):
    points, cells = square
    original = meshio.Mesh(points, [("triangle", cells)], point_data={"fixed": np.array([1, 1, 1, 1, 0])})
    w = smoothlab.Playground.from_meshio(original)
    assert "SCALARS fixed int 1" in w._file.decode()
    with pytest.raises(TypeError, match="from_meshio takes a meshio.Mesh, not ndarray"):
        smoothlab.Playground.from_meshio(points)


def test_to_meshio_writes_a_side(tmp_path, square):
    points, cells = square
    w = smoothlab.Playground(points, cells)
    out = tmp_path / "b.vtk"
    w.mesh_b.to_meshio().write(out)
    back = meshio.read(out)
    assert np.allclose(back.points[:, :2], points) and back.cells[0].type == "triangle"
