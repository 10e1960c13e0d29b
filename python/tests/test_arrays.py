"""Arrays in: what NumPy can see is checked in words naming what is wrong, and a good
mesh goes to the page as a .vtk text that holds exactly the arrays given."""

import numpy as np
import pytest

import smoothlab
from smoothlab.mesh import vtk_text, check_cells, check_points

from conftest import sections


def test_a_mesh_as_arrays_goes_to_the_page_exactly(square):
    points, cells = square
    points = points + np.array([1e-17, np.pi])  # digits that must survive the text
    w = smoothlab.Playground(points, cells)
    p, c, t, f = sections(w._file.decode())
    assert np.array_equal(p[:, :2], points) and np.all(p[:, 2] == 0)
    assert c == [[3, *row] for row in cells.tolist()]
    assert t == [5] * 4 and f is None
    assert w._file_name.endswith(".vtk")
    # before the page has reported, each side is the mesh as given
    got_points, got_cells = w.mesh_b
    assert np.array_equal(got_points, points) and got_cells[0][0] == "triangle"


def test_fixed_as_a_mask_or_as_point_numbers(square):
    points, cells = square
    by_numbers = smoothlab.Playground(points, cells, fixed=[0, 1, 2, 3])
    by_mask = smoothlab.Playground(points, cells, fixed=np.array([True, True, True, True, False]))
    assert sections(by_numbers._file.decode())[3] == [1, 1, 1, 1, 0]
    assert by_numbers._file == by_mask._file


def test_mixed_and_quadratic_blocks_keep_their_order_and_kinds():
    points = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [1, 1], [2, 1], [0.5, 0], [0.5, 0.5], [0, 0.5]], dtype=float)
    cells = [("quad", np.array([[1, 2, 5, 4]])), ("triangle6", np.array([[0, 1, 3, 6, 7, 8]])), ("line", np.array([[0, 1]]))]
    _, c, t, _ = sections(vtk_text(check_points(points), check_cells(cells, 9), None))
    assert t == [9, 22, 3] and c[1] == [6, 0, 1, 3, 6, 7, 8]


def test_3d_points_and_volume_elements():
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    w = smoothlab.Playground(points, [("tetra", np.array([[0, 1, 2, 3]]))])
    p, c, t, _ = sections(w._file.decode())
    assert np.array_equal(p, points) and t == [10]


@pytest.mark.parametrize(
    "points, cells, words",
    [
        (np.zeros((4, 4)), [[0, 1, 2]], r"points: an \(N, 2\) or \(N, 3\) array is needed, not one of shape \(4, 4\)"),
        (np.zeros(6), [[0, 1, 2]], r"not one of shape \(6,\)"),
        (np.array([[0, 0], [1, np.nan], [0, 1]]), [[0, 1, 2]], r"points\[1, 1\] is NaN"),
        (np.array([[0, 0], [1, 0], [np.inf, 1]]), [[0, 1, 2]], r"points\[2, 0\] is infinite"),
        (np.array([["a", "b"]]), [[0, 1, 2]], r"points: numbers are needed"),
        (np.zeros((0, 2)), [[0, 1, 2]], r"points: the array is empty"),
        (np.eye(3)[:, :2], np.array([[0, 1, 2], [0, 2, 17]]), r"cells\[1\] refers to point 17, but there are 3 points"),
        (np.eye(3)[:, :2], np.array([[0, 1, -1]]), r"cells\[0\] refers to point -1"),
        (np.eye(3)[:, :2], np.array([[0, 1, 2, 0, 1]]), r"k = 3 \(triangles\), 4 \(quads\).*not of shape \(1, 5\)"),
        (np.eye(3)[:, :2], np.array([[0.0, 1.0, 2.0]]), r"point numbers must be integers, not float64"),
        (np.eye(3)[:, :2], [("polygon", np.array([[0, 1, 2]]))], r"cells\[0\] \('polygon'\): smoothlab does not read 'polygon' cells; it reads triangle, quad"),
        (np.eye(3)[:, :2], [("triangle", np.array([[0, 1]]))], r"a triangle has 3 points, so an \(M, 3\) array is needed, not one of shape \(1, 2\)"),
        (np.eye(3)[:, :2], [("line", np.array([[0, 1]]))], r"cells: there are no elements"),
        (np.eye(3)[:, :2], "triangles", r"cells: give one \(M, k\) integer array, or a list of \(type, array\) pairs"),
    ],
)
def test_bad_arrays_are_refused_in_words(points, cells, words):
    with pytest.raises(ValueError, match=words):
        smoothlab.Playground(points, cells)


def test_bad_fixed_and_arguments_are_refused_in_words(square):
    points, cells = square
    with pytest.raises(ValueError, match=r"fixed\[1\] is point 9, but there are 5 points"):
        smoothlab.Playground(points, cells, fixed=[0, 9])
    with pytest.raises(ValueError, match=r"fixed: a boolean mask needs one flag a point, shape \(5,\)"):
        smoothlab.Playground(points, cells, fixed=np.ones(3, dtype=bool))
    with pytest.raises(ValueError, match="give one of points and cells, sample or figure, not points and cells and sample"):
        smoothlab.Playground(points, cells, sample="rand2d")
    with pytest.raises(ValueError, match="give both points and cells"):
        smoothlab.Playground(points)
    with pytest.raises(ValueError, match="give a mesh"):
        smoothlab.Playground()


def test_one_m_by_4_array_in_3d_is_named_not_guessed():
    """Tetrahedra given as one (M, 4) array were read as quads of a surface without a word."""
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], dtype=float)
    tets = np.array([[0, 1, 2, 3], [1, 2, 3, 4]])
    for make in (smoothlab.Mesh, smoothlab.Playground):
        with pytest.raises(ValueError, match=r"cells: one \(M, 4\) array with points in 3D .* \[\('quad', cells\)\] or \[\('tetra', cells\)\]"):
            make(points, tets)
    assert smoothlab.Mesh(points, [("tetra", tets)]).kind == "volume"
    # quads with meshio's z = 0 are quads
    flat = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    assert smoothlab.Mesh(flat, np.array([[0, 1, 2, 3]])).cells[0][0] == "quad"


@pytest.mark.parametrize(
    "cells, words",
    [
        ([[0, 1, 2], [0, 2]], r"^cells: the rows have different lengths; each a row of one \(M, k\) array lists the same number"),
        ([("triangle", [[0, 1, 2], [0, 2]])], r"^cells\[0\] \('triangle'\): the rows have different lengths; each a triangle"),
    ],
)
def test_ragged_cells_are_named(square, cells, words):
    points, _ = square
    for make in (smoothlab.Mesh, smoothlab.Playground):
        with pytest.raises(ValueError, match=words):
            make(points, cells)


def test_fixed_empty_fixes_nothing_and_a_0_1_integer_mask_is_refused(square):
    points, cells = square
    assert not smoothlab.Mesh(points, cells, fixed=[]).fixed.any()
    assert sections(smoothlab.Playground(points, cells, fixed=[])._file.decode())[3] == [0] * 5
    for make in (smoothlab.Mesh, smoothlab.Playground):
        with pytest.raises(ValueError, match=r"fixed: 5 integers, all 0 or 1, one a point, read both as a mask and as point numbers"):
            make(points, cells, fixed=[1, 0, 0, 0, 1])
    # booleans or point numbers say it without doubt
    mask = smoothlab.Mesh(points, cells, fixed=np.array([1, 0, 0, 0, 1], dtype=bool)).fixed
    assert mask.tolist() == [True, False, False, False, True]
    assert smoothlab.Mesh(points, cells, fixed=[1, 0]).fixed.tolist() == [True, True, False, False, False]


def test_the_cores_refusals_name_the_arguments():
    points = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], dtype=float)
    with pytest.raises(ValueError, match=r"^cells\[1\] \('triangle'\)\[0\]: .*(twice|repeated)"):
        smoothlab.Mesh(points, [("quad", np.array([[0, 1, 3, 2]])), ("triangle", np.array([[1, 3, 3]]))])
    with pytest.raises(ValueError, match=r"^cells\[1\]: .*(twice|repeated)"):
        smoothlab.Mesh(points, np.array([[0, 1, 2], [1, 1, 3]]))
    with pytest.raises(ValueError, match=r"^points\[2\]: coordinate .* too large"):
        smoothlab.Mesh(np.array([[0, 0], [1, 0], [0, 1e308]]), np.array([[0, 1, 2]]))
