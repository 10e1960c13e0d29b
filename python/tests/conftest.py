import pathlib

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def sections(text):
    """The .vtk text's points, cells, types and fixed flags, read back by hand."""
    lines = text.splitlines()
    at = lambda key: next(i for i, l in enumerate(lines) if l.startswith(key))
    n = int(lines[at("POINTS")].split()[1])
    points = np.array([[float(t) for t in l.split()] for l in lines[at("POINTS") + 1 : at("POINTS") + 1 + n]])
    m = int(lines[at("CELLS")].split()[1])
    cells = [[int(t) for t in l.split()] for l in lines[at("CELLS") + 1 : at("CELLS") + 1 + m]]
    types = [int(l) for l in lines[at("CELL_TYPES") + 1 : at("CELL_TYPES") + 1 + m]]
    fixed = None
    if any(l.startswith("POINT_DATA") for l in lines):
        fixed = [int(l) for l in lines[at("LOOKUP_TABLE") + 1 : at("LOOKUP_TABLE") + 1 + n]]
    return points, cells, types, fixed


@pytest.fixture
def square():
    """Four triangles round a free centre: points (5, 2) and cells (4, 3)."""
    points = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [0.3, 0.6]])
    cells = np.array([[0, 1, 4], [1, 3, 4], [3, 2, 4], [2, 0, 4]])
    return points, cells
