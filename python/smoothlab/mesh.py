"""Meshes as arrays, in and out of the widget.

In: ``points`` an (N, 2) or (N, 3) float array; ``cells`` meshio's list of ``(type,
array)`` (or its ``CellBlock``s), or one (M, k) integer array of triangles (k = 3), quads
(4), 6-node triangles (6), 8- or 9-node quads (8, 9); ``fixed`` a boolean mask of the
points or a list of point numbers. What NumPy can see is checked here, each refusal a
``ValueError`` naming what is wrong; the mesh then goes to the page as the text of a legacy
``.vtk`` file, which the page's reader (the Rust core's, the command-line tool's) reads
with its own checks and messages (the widget's ``error``).

Out: what the page sends of a side (its arrays, as its ``.vtk`` export holds them) as a
:class:`Mesh`: points, cells in meshio's form and fixed flags.
"""

from __future__ import annotations

import io
from typing import Any, Iterator, List, Optional, Sequence, Tuple

import numpy as np

# meshio's cell type names, the VTK cell type of each, and its number of nodes (meshio
# orders a cell's nodes as VTK does); the kinds the page reads, and the vertex and line
# cells that mark fixed points (as a Gmsh file's point and line elements do)
CELL_TYPES = {
    "triangle": (5, 3),
    "quad": (9, 4),
    "triangle6": (22, 6),
    "quad8": (23, 8),
    "quad9": (28, 9),
    "tetra": (10, 4),
    "hexahedron": (12, 8),
    "wedge": (13, 6),
    "pyramid": (14, 5),
    "tetra10": (24, 10),
    "hexahedron20": (25, 20),
    "hexahedron27": (29, 27),
    "vertex": (1, 1),
    "line": (3, 2),
    "line3": (21, 3),
}
MARKERS = ("vertex", "line", "line3")
VTK_NAMES = {code: name for name, (code, _) in CELL_TYPES.items()}
# one (M, k) array: the planar and surface kinds by their number of nodes
BY_NODE_COUNT = {3: "triangle", 4: "quad", 6: "triangle6", 8: "quad8", 9: "quad9"}

Cells = List[Tuple[str, np.ndarray]]


def _words(names: Sequence[str]) -> str:
    return ", ".join(names[:-1]) + " or " + names[-1] if len(names) > 1 else "".join(names)


def check_points(points: Any) -> np.ndarray:
    """The points as an (N, 2) or (N, 3) float64 array, or a ValueError saying what is wrong."""
    try:
        p = np.asarray(points)
    except Exception as e:  # a ragged list
        raise ValueError(f"points: cannot be read as an array ({e})") from None
    if p.dtype == object or not (np.issubdtype(p.dtype, np.floating) or np.issubdtype(p.dtype, np.integer)):
        raise ValueError(f"points: numbers are needed, not {p.dtype} values")
    if p.ndim != 2 or p.shape[1] not in (2, 3):
        raise ValueError(f"points: an (N, 2) or (N, 3) array is needed, not one of shape {p.shape}")
    if p.shape[0] == 0:
        raise ValueError("points: the array is empty")
    p = p.astype(np.float64)
    bad = np.argwhere(~np.isfinite(p))
    if len(bad):
        i, j = bad[0]
        what = "NaN" if np.isnan(p[i, j]) else "infinite"
        more = f" (and {len(bad) - 1} more)" if len(bad) > 1 else ""
        raise ValueError(f"points[{i}, {j}] is {what}{more}: every coordinate must be a finite number")
    return p


def check_cells(cells: Any, n_points: int) -> Cells:
    """The cells as meshio's ``[(type, (M, k) int array)]``, or a ValueError naming the
    block, the cell and what is wrong (an unknown type, a wrong shape, a point number out
    of range)."""
    if isinstance(cells, np.ndarray) or (isinstance(cells, (list, tuple)) and cells and not _is_block(cells[0])):
        c = np.asarray(cells)
        if c.ndim != 2 or c.shape[1] not in BY_NODE_COUNT:
            raise ValueError(
                f"cells: one array must be (M, k) with k = 3 (triangles), 4 (quads), 6 (6-node triangles), "
                f"8 or 9 (8- or 9-node quads), not of shape {c.shape}; give volume elements as meshio's "
                f"list of (type, array), e.g. [('tetra', array)]"
            )
        blocks = [(BY_NODE_COUNT[c.shape[1]], c)]
    else:
        try:
            blocks = [_block(b) for b in cells]
        except (TypeError, ValueError):
            raise ValueError(
                "cells: give one (M, k) integer array, or a list of (type, array) pairs as meshio holds them"
            ) from None
    out: Cells = []
    for b, (kind, data) in enumerate(blocks):
        where = f"cells[{b}] ({kind!r})" if len(blocks) > 1 or not isinstance(cells, np.ndarray) else "cells"
        if kind not in CELL_TYPES:
            raise ValueError(
                f"{where}: smoothlab does not read {kind!r} cells; it reads "
                f"{_words([k for k in CELL_TYPES if k not in MARKERS])} "
                f"(and {_words(list(MARKERS))} cells, which fix their points)"
            )
        k = CELL_TYPES[kind][1]
        a = np.asarray(data)
        if a.size == 0:
            continue
        if not np.issubdtype(a.dtype, np.integer):
            raise ValueError(f"{where}: point numbers must be integers, not {a.dtype} values")
        if a.ndim == 1 and k == 1:
            a = a.reshape(-1, 1)
        if a.ndim != 2 or a.shape[1] != k:
            raise ValueError(f"{where}: a {kind} has {k} points, so an (M, {k}) array is needed, not one of shape {a.shape}")
        bad = np.argwhere((a < 0) | (a >= n_points))
        if len(bad):
            i, j = bad[0]
            raise ValueError(
                f"{where}[{i}] refers to point {a[i, j]}, but there are {n_points} points (numbered 0 to {n_points - 1})"
            )
        out.append((kind, a.astype(np.int64)))
    if not any(kind not in MARKERS for kind, _ in out):
        raise ValueError("cells: there are no elements (only vertex and line cells, or none at all)")
    return out


def _is_block(b: Any) -> bool:
    return hasattr(b, "type") and hasattr(b, "data") or (isinstance(b, (tuple, list)) and len(b) == 2 and isinstance(b[0], str))


def _block(b: Any) -> Tuple[str, Any]:
    if hasattr(b, "type") and hasattr(b, "data"):  # meshio's CellBlock
        return str(b.type), b.data
    kind, data = b
    if not isinstance(kind, str):
        raise TypeError("a cell type is a name")
    return kind, data


def check_fixed(fixed: Any, n_points: int) -> Optional[np.ndarray]:
    """The fixed flags as a boolean mask of the points (None: the page decides, fixing the
    boundary and the points of vertex and line cells), from a mask or point numbers."""
    if fixed is None:
        return None
    f = np.asarray(fixed)
    if f.dtype == bool:
        if f.shape != (n_points,):
            raise ValueError(f"fixed: a boolean mask needs one flag a point, shape ({n_points},), not {f.shape}")
        return f
    if not np.issubdtype(f.dtype, np.integer) or f.ndim != 1:
        raise ValueError(f"fixed: give a boolean mask of the points or a list of point numbers, not a {f.dtype} array of shape {f.shape}")
    bad = np.flatnonzero((f < 0) | (f >= n_points))
    if len(bad):
        raise ValueError(f"fixed[{bad[0]}] is point {f[bad[0]]}, but there are {n_points} points (numbered 0 to {n_points - 1})")
    mask = np.zeros(n_points, dtype=bool)
    mask[f] = True
    return mask


def vtk_text(points: np.ndarray, cells: Cells, fixed: Optional[np.ndarray]) -> str:
    """A legacy VTK ``UNSTRUCTURED_GRID`` (ASCII) of checked arrays, coordinates written to
    17 significant digits (each reads back to the same double)."""
    out = io.StringIO()
    n = len(points)
    out.write(f"# vtk DataFile Version 3.0\nsmoothlab widget mesh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {n} double\n")
    xyz = points if points.shape[1] == 3 else np.column_stack([points, np.zeros(n)])
    np.savetxt(out, xyz, fmt="%.17g")
    m = sum(len(a) for _, a in cells)
    size = sum(a.size + len(a) for _, a in cells)
    out.write(f"CELLS {m} {size}\n")
    for _, a in cells:
        np.savetxt(out, np.column_stack([np.full(len(a), a.shape[1]), a]), fmt="%d")
    out.write(f"CELL_TYPES {m}\n")
    for kind, a in cells:
        np.savetxt(out, np.full(len(a), CELL_TYPES[kind][0]), fmt="%d")
    if fixed is not None:
        out.write(f"POINT_DATA {n}\nSCALARS fixed int 1\nLOOKUP_TABLE default\n")
        np.savetxt(out, fixed.astype(np.int64), fmt="%d")
    return out.getvalue()


class Mesh:
    """A side's mesh: ``points`` (N, 2) or (N, 3), ``cells`` as meshio holds them (a list
    of ``(type, (M, k) array)``), ``fixed`` a boolean mask of the points (None when not
    known: the mesh as given, before the page has reported it). ``points, cells = mesh``
    unpacks it."""

    def __init__(self, points: np.ndarray, cells: Cells, fixed: Optional[np.ndarray] = None):
        self.points = points
        self.cells = cells
        self.fixed = fixed

    @classmethod
    def from_page(cls, state: dict) -> "Mesh":
        """A side as the page sends it (www/app/host.js, the widget's ``_mesh_a``/``_mesh_b``):
        ``{dim, points, cells: [{vtk_type, per_cell, nodes}], fixed}``, the arrays as bytes."""
        dim = int(state["dim"])
        points = np.frombuffer(bytes(state["points"]), dtype="<f8").reshape(-1, dim).copy()
        cells = []
        for c in state["cells"]:
            code = int(c["vtk_type"])
            if code not in VTK_NAMES:
                raise ValueError(f"the page sent cells of VTK type {code}, which has no meshio name here")
            nodes = np.frombuffer(bytes(c["nodes"]), dtype="<u4").astype(np.int64).reshape(-1, int(c["per_cell"]))
            cells.append((VTK_NAMES[code], nodes))
        fixed = np.frombuffer(bytes(state["fixed"]), dtype=np.uint8).astype(bool)
        return cls(points, cells, fixed)

    def __iter__(self) -> Iterator[Any]:
        yield self.points
        yield self.cells

    def __repr__(self) -> str:
        kinds = ", ".join(f"{len(a)} {k}" for k, a in self.cells)
        return f"Mesh({len(self.points)} points in {self.points.shape[1]}D; {kinds})"

    def to_meshio(self):
        """The mesh as a ``meshio.Mesh`` (meshio is needed: ``pip install meshio``), the
        fixed flags as point data ``fixed`` when known."""
        try:
            import meshio
        except ImportError:
            raise ImportError("to_meshio needs meshio: pip install meshio") from None
        point_data = {} if self.fixed is None else {"fixed": self.fixed.astype(np.int64)}
        return meshio.Mesh(self.points, [(k, a) for k, a in self.cells], point_data=point_data)
