"""Meshes: the headless front door (:func:`read`, :class:`Mesh`, :meth:`Mesh.smooth`,
:meth:`Mesh.stats`, :func:`write`, :func:`render`) over the native core, and arrays in and
out of it and of the widget.

In: ``points`` an (N, 2) or (N, 3) float array; ``cells`` meshio's list of ``(type,
array)`` (or its ``CellBlock``s), or one (M, k) integer array of triangles (k = 3), quads
(4), 6-node triangles (6), 8- or 9-node quads (8, 9); ``fixed`` a boolean mask of the
points or a list of point numbers. What NumPy can see is checked here, each refusal a
``ValueError`` naming what is wrong; the core then builds the mesh a ``.vtk`` file of the
arrays reads as, with its own checks (the widget sends the page that ``.vtk`` text).

Out: a mesh's arrays as the ``.vtk`` writer holds them (points, cells in meshio's form,
fixed flags), and what the page sends of a side, as a :class:`Mesh`.

>>> import smoothlab
>>> bool(smoothlab.Mesh([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]], fixed=[]).fixed.any())
False
"""

from __future__ import annotations

import io
import json
import os
import re
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native

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


def check_cells(cells: Any, n_points: int, points: Optional[np.ndarray] = None) -> Cells:
    """The cells as meshio's ``[(type, (M, k) int array)]``, or a ValueError naming the
    block, the cell and what is wrong (an unknown type, a wrong shape, rows of different
    lengths, a point number out of range). With ``points`` (checked), one (M, 4) array
    whose points are not all in the plane z = constant is refused: it could be quads of a
    surface or tetrahedra, and the list of ``(type, array)`` says which."""
    if isinstance(cells, np.ndarray) or (isinstance(cells, (list, tuple)) and cells and not _is_block(cells[0])):
        c = _array(cells, "cells", "a row of one (M, k) array")
        if c.ndim != 2 or c.shape[1] not in BY_NODE_COUNT:
            raise ValueError(
                f"cells: one array must be (M, k) with k = 3 (triangles), 4 (quads), 6 (6-node triangles), "
                f"8 or 9 (8- or 9-node quads), not of shape {c.shape}; give volume elements as meshio's "
                f"list of (type, array), e.g. [('tetra', array)]"
            )
        if c.shape[1] == 4 and points is not None and points.shape[1] == 3 and np.ptp(points[:, 2]) != 0:
            raise ValueError(
                "cells: one (M, 4) array with points in 3D (not all at one z) could be quads of a surface or "
                "tetrahedra; say which as meshio does: [('quad', cells)] or [('tetra', cells)]"
            )
        blocks = [(BY_NODE_COUNT[c.shape[1]], c)]
        single = True
    else:
        single = False
        try:
            blocks = [_block(b) for b in cells]
        except (TypeError, ValueError):
            raise ValueError(
                "cells: give one (M, k) integer array, or a list of (type, array) pairs as meshio holds them"
            ) from None
    out: Cells = []
    for b, (kind, data) in enumerate(blocks):
        where = "cells" if single else f"cells[{b}] ({kind!r})"
        if kind not in CELL_TYPES:
            raise ValueError(
                f"{where}: smoothlab does not read {kind!r} cells; it reads "
                f"{_words([k for k in CELL_TYPES if k not in MARKERS])} "
                f"(and {_words(list(MARKERS))} cells, which fix their points)"
            )
        k = CELL_TYPES[kind][1]
        a = _array(data, where, f"a {kind}")
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


def _array(data: Any, where: str, row: str) -> np.ndarray:
    """``data`` as an array, or a ValueError naming ``where`` when its rows differ in
    length (NumPy's own words name no argument)."""
    try:
        a = np.asarray(data)
    except ValueError:
        a = None
    if a is None or (a.dtype == object and a.ndim >= 1):
        raise ValueError(
            f"{where}: the rows have different lengths; each {row} lists the same number of points "
            f"(give mixed kinds as meshio's list of (type, array) pairs, one pair a kind)"
        ) from None
    return a


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
    """The fixed flags as a boolean mask of the points (None: smoothlab decides, fixing the
    boundary and the points of vertex and line cells), from a boolean mask or a list of
    point numbers (``[]``: no point is fixed, the boundary moves too). An integer array
    of 0s and 1s, one a point, reads both ways and is refused: give it as booleans."""
    if fixed is None:
        return None
    f = np.asarray(fixed)
    if f.ndim == 1 and f.size == 0:
        return np.zeros(n_points, dtype=bool)
    if f.dtype == bool:
        if f.shape != (n_points,):
            raise ValueError(f"fixed: a boolean mask needs one flag a point, shape ({n_points},), not {f.shape}")
        return f
    if not np.issubdtype(f.dtype, np.integer) or f.ndim != 1:
        raise ValueError(f"fixed: give a boolean mask of the points or a list of point numbers, not a {f.dtype} array of shape {f.shape}")
    if f.shape == (n_points,) and np.all((f == 0) | (f == 1)):
        raise ValueError(
            f"fixed: {n_points} integers, all 0 or 1, one a point, read both as a mask and as point numbers; "
            f"give a mask as booleans (np.asarray(fixed, dtype=bool)) or the numbers of the fixed points"
        )
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


def _cells_error(e: ValueError, cells: Cells) -> ValueError:
    """The core's refusal of arrays, its ``element E`` and ``node N`` said as the arguments'
    ``cells[B][I]`` and ``points[N]`` (a planar mesh or a surface: the core numbers the
    cells in order, as given)."""
    text = str(e)
    m = re.match(r"element (\d+): (.*)", text, re.S)
    if m and not any(CELL_TYPES[k][0] in VOLUME_TYPES for k, _ in cells):
        e_at = int(m.group(1))
        for b, (kind, a) in enumerate(cells):
            if e_at < len(a):
                where = f"cells[{b}] ({kind!r})[{e_at}]" if len(cells) > 1 else f"cells[{e_at}]"
                return ValueError(f"{where}: {m.group(2)}")
            e_at -= len(a)
    m = re.match(r"node (\d+): (.*)", text, re.S)
    if m:
        return ValueError(f"points[{m.group(1)}]: {m.group(2)}")
    return ValueError(f"cells: {text}")


VOLUME_TYPES = {code for name, (code, _) in CELL_TYPES.items() if name in ("tetra", "hexahedron", "wedge", "pyramid", "tetra10", "hexahedron20", "hexahedron27")}


class Mesh:
    """A mesh smoothlab holds: planar, a surface in 3D, or a volume mesh.

    ``Mesh(points, cells, fixed=None)`` takes ``points`` as an (N, 2) or (N, 3) array,
    ``cells`` as meshio holds them (a list of ``(type, array)``) or as one (M, k) array of
    triangles or quads, and ``fixed`` as a boolean mask or a list of point numbers (None:
    the boundary and the points of vertex and line cells are fixed). What a ``.vtk`` file
    of these arrays would be read as, with the same checks: a refusal is a ``ValueError``
    naming the argument (``cells[1]``, ``points[3, 0]``, ``fixed``).

    ``points``, ``cells`` and ``fixed`` are NumPy arrays of the mesh as it is now (read
    only: a new ``Mesh`` is a changed mesh); ``points, cells = mesh`` unpacks it.

    >>> import numpy as np, smoothlab
    >>> points = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.8, 0.7]])
    >>> mesh = smoothlab.Mesh(points, np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))
    >>> mesh
    Mesh(5 points in 2D; 4 triangle)
    >>> report = mesh.smooth()
    >>> bool(np.allclose(mesh.points[4], [0.5, 0.5], atol=1e-3)), report.inverted
    (True, 0)
    """

    def __init__(self, points: Any, cells: Any, fixed: Any = None):
        p = check_points(points)
        c = check_cells(cells, len(p), p)
        f = check_fixed(fixed, len(p))
        blocks = [(CELL_TYPES[k][0], a.shape[1], np.ascontiguousarray(a, dtype=np.uint32).reshape(-1)) for k, a in c]
        try:
            model = _native.Model.from_arrays(p.shape[1], np.ascontiguousarray(p).reshape(-1), blocks, f)
        except ValueError as e:
            raise _cells_error(e, c) from None
        self._set(model, p.shape[1])

    def _set(self, model: Any, dim: Optional[int]) -> None:
        self._model = model
        # points given with 3 coordinates in the plane z = 0 come back with 3 (meshio's)
        self._dim = dim
        self._arrays: Optional[Tuple[np.ndarray, Cells, np.ndarray]] = None

    @classmethod
    def _wrap(cls, model: Any, dim: Optional[int] = None) -> "Mesh":
        mesh = cls.__new__(cls)
        mesh._set(model, dim)
        return mesh

    def _get(self) -> Tuple[np.ndarray, Cells, np.ndarray]:
        if self._arrays is None:
            flat, dim, blocks, fixed = self._model.arrays()
            points = flat.reshape(-1, dim)
            if self._dim == 3 and dim == 2:
                points = np.column_stack([points, np.zeros(len(points))])
            cells = [(VTK_NAMES[t], nodes.reshape(-1, k).astype(np.int64)) for t, k, nodes in blocks]
            for a in (points, fixed, *(a for _, a in cells)):
                a.flags.writeable = False
            self._arrays = (points, cells, fixed)
        return self._arrays

    @property
    def points(self) -> np.ndarray:
        """The points, (N, 2) for a mesh in the xy plane, else (N, 3), float64 (read only)."""
        return self._get()[0]

    @property
    def cells(self) -> Cells:
        """The cells as meshio holds them, ``[(type, (M, k) int64 array)]``, in their order
        (a volume mesh's boundary faces after its elements)."""
        return self._get()[1]

    @property
    def fixed(self) -> np.ndarray:
        """One flag a point: True where smoothing never moves it."""
        return self._get()[2]

    @property
    def kind(self) -> str:
        """``"planar"``, ``"surface"`` (in 3D) or ``"volume"``.

        >>> import smoothlab
        >>> smoothlab.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [("tetra", [[0, 1, 2, 3]])]).kind
        'volume'
        """
        return self._model.kind

    def smooth(self, **settings: Any) -> "Report":
        """Smooths the mesh in place as ``smoothlab smooth`` does, and says what each pass
        did. The settings are the command line's (``smoothlab.settings()`` lists them):
        ``objective``, ``strategy``, ``threshold``, ``passes``, ``order``, ``max_iter``,
        ``penalty``, ``pass_through_folds``, ``finish``, ``target``, ``slide_curves``,
        ``boundary``, ``feature_angle``; those left out take its defaults. Once the passes leave the mesh valid, ``finish`` more (3
        by default) lift its worst element; ``report.finish`` says how many ran.
        The default target, ``"stretch"``, keeps each element's stretch as read,
        averaged along its layer (a boundary layer's rows stay thin), and is the ideal
        element where the mesh has no stretch made on purpose; ``target="ideal"`` is the
        papers' setting, ``target="input"`` measures each corner against itself as it was. ``boundary="slide"`` lets a mesh's boundary nodes
        slide on the boundary as loaded (a surface's along its open edges and feature curves;
        corners stay; ``report.boundary``
        says how many slid and how far from it they are). A setting out of range, or one the strategy would not use, is a
        ``ValueError`` naming it. Other Python threads run meanwhile.

        >>> import numpy as np, smoothlab
        >>> mesh = smoothlab.Mesh(np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.8, 0.7]]), np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))
        >>> report = mesh.smooth(strategy="opt", objective="condition", passes=2)
        >>> len(report.passes), report.finish, report.strategy
        (5, 3, 'opt')
        >>> mesh.smooth(passes=0)
        Traceback (most recent call last):
        ...
        ValueError: passes: 0 asked: give 1 to 10000
        """
        report = Report(self._model.smooth(**settings))
        self._arrays = None
        return report

    def stats(self) -> Dict[str, Any]:
        """The statistics ``smoothlab stats --json`` prints, as a dict.

        >>> import numpy as np, smoothlab
        >>> mesh = smoothlab.Mesh(np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.5]]), np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))
        >>> s = mesh.stats()
        >>> s["elements"], s["free_nodes"], round(s["min_angle_deg"])
        (4, 1, 45)
        """
        return json.loads(self._model.stats())

    def copy(self) -> "Mesh":
        """A copy: smoothing it leaves this mesh as it is.

        >>> import smoothlab
        >>> a = smoothlab.Mesh([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]])
        >>> b = a.copy()
        >>> b is a, bool((b.points == a.points).all())
        (False, True)
        """
        return Mesh._wrap(self._model.copy(), self._dim)

    @classmethod
    def from_meshio(cls, mesh: Any, fixed: Any = None) -> "Mesh":
        """A mesh from a ``meshio.Mesh``: its points and cell blocks; its point data
        ``fixed`` (as smoothlab writes it) fixes points when ``fixed`` is not given.

        >>> import meshio, smoothlab
        >>> m = meshio.Mesh([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], [("triangle", [[0, 1, 2]])])
        >>> smoothlab.Mesh.from_meshio(m)
        Mesh(3 points in 2D; 1 triangle)
        """
        if not (hasattr(mesh, "points") and hasattr(mesh, "cells")):
            raise ValueError(f"mesh: from_meshio takes a meshio.Mesh, not {type(mesh).__name__}")
        if fixed is None and "fixed" in getattr(mesh, "point_data", {}):
            fixed = np.asarray(mesh.point_data["fixed"]).reshape(-1) != 0
        return cls(mesh.points, list(mesh.cells), fixed)

    @classmethod
    def from_page(cls, state: dict, dim: Optional[int] = None) -> "Mesh":
        """A side as the page sends it (www/app/host.js, the widget's ``_mesh_a``/``_mesh_b``):
        ``{dim, points, cells: [{vtk_type, per_cell, nodes}], fixed}``, the arrays as bytes;
        ``dim`` 3 gives a mesh in the xy plane its z = 0 back."""
        d = int(state["dim"])
        points = np.frombuffer(bytes(state["points"]), dtype="<f8").astype(np.float64)
        blocks = []
        for c in state["cells"]:
            code = int(c["vtk_type"])
            if code not in VTK_NAMES:
                raise ValueError(f"the page sent cells of VTK type {code}, which has no meshio name here")
            blocks.append((code, int(c["per_cell"]), np.frombuffer(bytes(c["nodes"]), dtype="<u4").astype(np.uint32)))
        fixed = np.frombuffer(bytes(state["fixed"]), dtype=np.uint8) != 0
        return cls._wrap(_native.Model.from_arrays(d, points, blocks, fixed), dim)

    def __iter__(self) -> Iterator[Any]:
        yield self.points
        yield self.cells

    def __repr__(self) -> str:
        kinds = ", ".join(f"{len(a)} {k}" for k, a in self.cells)
        return f"Mesh({len(self.points)} points in {self.points.shape[1]}D; {kinds})"

    def to_meshio(self):
        """The mesh as a ``meshio.Mesh`` (meshio is needed: ``pip install meshio``), the
        fixed flags as point data ``fixed``.

        >>> import smoothlab
        >>> smoothlab.Mesh([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]]).to_meshio().cells[0].type
        'triangle'
        """
        try:
            import meshio
        except ImportError:
            raise ImportError("to_meshio needs meshio: pip install meshio") from None
        return meshio.Mesh(self.points, [(k, a) for k, a in self.cells], point_data={"fixed": self.fixed.astype(np.int64)})


class Report:
    """What :meth:`Mesh.smooth` did, as ``smoothlab smooth --json`` prints it:
    ``objective``, ``strategy``, ``target``, ``boundary`` (with sliding boundaries: what slid
    and how far from the boundary as loaded; else ``None``), ``passes`` (a dict a pass),
    ``finish`` (how many of them, the last, are the finish), ``final`` (the statistics of
    :meth:`Mesh.stats`), ``untangling_impossible`` (inverted elements no move can repair,
    and why) and ``time_ms``; ``json`` is the text itself.

    >>> import numpy as np, smoothlab
    >>> mesh = smoothlab.Mesh(np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.8, 0.7]]), np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))
    >>> report = mesh.smooth()
    >>> report.objective, len(report.passes), report.finish, report.passes[0]["pass"], report.inverted
    ('new', 6, 3, 1, 0)
    """

    def __init__(self, text: str):
        self.json = text
        d = json.loads(text)
        self.objective: str = d["objective"]
        self.strategy: str = d["strategy"]
        self.target: str = d["target"]
        self.boundary: Optional[Dict[str, Any]] = d.get("boundary")
        self.passes: List[Dict[str, Any]] = d["passes"]
        self.finish: int = d["finish"]
        self.final: Dict[str, Any] = d["final"]
        self.untangling_impossible: List[Dict[str, Any]] = d["untangling_impossible"]
        self.time_ms: float = d["time_ms"]

    @property
    def inverted(self) -> int:
        """Inverted elements after the run."""
        return int(self.final["inverted"])

    def as_dict(self) -> Dict[str, Any]:
        """The report as the dict its JSON holds."""
        return json.loads(self.json)

    def __repr__(self) -> str:
        n = len(self.passes)
        return f"Report({self.objective}, {self.strategy}, {n} pass{'' if n == 1 else 'es'}, {self.inverted} inverted)"


def read(path: Union[str, "os.PathLike[str]"]) -> Mesh:
    """Reads a mesh file: ``.msh`` (Gmsh 2.2 and 4.1), ``.vtk``, ``.node``/``.ele``,
    ``.obj``, ``.off`` or ``.mesh`` (Medit), the format by its extension, as the
    command-line tool reads it. A file smoothlab cannot read is a ``ValueError`` that
    names it and its line; one that cannot be opened an ``OSError``.

    >>> import pathlib, tempfile, smoothlab
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "tri.obj"
    >>> _ = path.write_text("v 0 0 0\\nv 1 0 0\\nv 0 1 0\\nf 1 2 3\\n")
    >>> smoothlab.read(path)
    Mesh(3 points in 2D; 1 triangle)
    >>> _ = path.write_text("v 0 0 0\\nf 1 2 3\\n")
    >>> smoothlab.read(path)
    Traceback (most recent call last):
    ...
    ValueError: ...tri.obj: ...line 2...
    """
    return Mesh._wrap(_native.Model.read(os.fspath(path)))


def write(mesh: Mesh, path: Union[str, "os.PathLike[str]"], msh_version: Optional[str] = None) -> None:
    """Writes the mesh, the format by the extension, as ``smoothlab smooth IN -o OUT``
    writes it (byte for byte); ``msh_version`` ``"2.2"`` (the default) or ``"4.1"`` for
    ``.msh``.

    >>> import pathlib, tempfile, smoothlab
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "tri.vtk"
    >>> smoothlab.write(smoothlab.Mesh([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]]), out)
    >>> out.read_text().splitlines()[0]
    '# vtk DataFile Version 3.0'
    """
    if not isinstance(mesh, Mesh):
        raise ValueError(f"mesh: give a smoothlab.Mesh (smoothlab.read, smoothlab.Mesh), not {type(mesh).__name__}")
    mesh._model.write(os.fspath(path), msh_version)


VIEWS: Tuple[str, ...] = tuple(_native.VIEWS)


def render(
    mesh: Mesh,
    path: Union[str, "os.PathLike[str]"],
    view: str = "mesh",
    *,
    size: Optional[Tuple[int, int]] = None,
    dpr: Optional[float] = None,
    metric: Optional[str] = None,
    theme: Optional[str] = None,
    camera: Union[None, str, Sequence[float]] = None,
    cut: Union[None, str, Tuple[str, float]] = None,
    node: Optional[int] = None,
    objective: Union[None, str, Sequence[str]] = None,
    passes: Optional[int] = None,
    strategy: Optional[str] = None,
    threshold: Optional[float] = None,
    order: Optional[str] = None,
    max_iter: Optional[int] = None,
    penalty: Optional[str] = None,
) -> None:
    """Draws the mesh to a PNG file as ``smoothlab render IN -o OUT --view VIEW`` does,
    by the same code, from the mesh as it is now (the tool's bytes for the same options).

    ``view``: ``"mesh"`` (coloured by ``metric``: ``"alpha"``, ``"angle"`` or
    ``"condition"``; ``node`` marks a node's star), ``"compare"`` (the old max-min
    objective beside the new smooth one after ``passes``, 3 by default, with their
    statistics), ``"levelset"`` (a node's level sets), ``"history"`` (per-pass curves, or
    a node's solve) or ``"histogram"`` (angles). A surface is drawn in the 3D view
    (``camera``: yaw and pitch in degrees and a zoom, ``(30, 25, 1)`` by default), a volume
    mesh cut by a plane (``cut``: ``("z", 0.5)``, an axis and a fraction of its extent).
    ``objective`` ``"old"``, ``"new"`` or both; ``strategy``, ``threshold``, ``order``,
    ``max_iter`` and ``penalty`` as for ``render``'s passes; ``size`` (width, height) in
    pixels, ``dpr`` the pixel ratio, ``theme`` ``"light"`` or ``"dark"``. Left out, each
    takes the tool's default.

    >>> import pathlib, tempfile, numpy as np, smoothlab
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "star.png"
    >>> mesh = smoothlab.Mesh(np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.8, 0.7]]), np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))
    >>> smoothlab.render(mesh, out, "compare", passes=1, size=(600, 300))
    >>> out.read_bytes()[:4]
    b'\\x89PNG'
    """
    if not isinstance(mesh, Mesh):
        raise ValueError(f"mesh: give a smoothlab.Mesh (smoothlab.read, smoothlab.Mesh), not {type(mesh).__name__}")
    if camera is not None and not isinstance(camera, str):
        try:
            camera = ",".join(repr(float(c)) for c in camera)
        except (TypeError, ValueError):
            raise ValueError(f"camera: give (yaw, pitch) or (yaw, pitch, zoom) in numbers, not {camera!r}") from None
    if cut is not None and not isinstance(cut, str):
        try:
            axis, at = cut
        except (TypeError, ValueError):
            raise ValueError(f"cut: give (axis, fraction) such as ('z', 0.5), or 'z=0.5', not {cut!r}") from None
        cut = f"{axis}={at}"
    if objective is not None and not isinstance(objective, str):
        objective = ",".join(map(str, objective))
    mesh._model.render(
        os.fspath(path), view=view, size=size, dpr=dpr, metric=metric, theme=theme, camera=camera, cut=cut,
        node=node, objective=objective, passes=passes, strategy=strategy, threshold=threshold, order=order,
        max_iter=max_iter, penalty=penalty,
    )


def settings() -> Dict[str, Optional[List[str]]]:
    """The settings :meth:`Mesh.smooth` takes (the command line's), each with its choices
    when it names one (None for numbers and flags).

    >>> import smoothlab
    >>> smoothlab.settings()["strategy"]
    ['laplace', 'smart', 'opt', 'c1', 'c2', 'c3', 'rules']
    """
    return dict(_native.settings())
