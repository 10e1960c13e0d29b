"""smoothlab: mesh smoothing from Python, and the playground page as a notebook widget.

Headless, as the command-line tool: ``read`` a mesh file (planar, a surface in 3D or a
volume mesh), ``Mesh.smooth`` it with the command line's settings, ``Mesh.stats``,
``write`` it back (the tool's bytes), ``render`` it to a PNG; ``Mesh(points, cells,
fixed=None)`` and ``Mesh.from_meshio`` take arrays, ``.points``, ``.cells`` and
``.fixed`` give them back as NumPy arrays.

>>> import numpy as np, smoothlab
>>> mesh = smoothlab.Mesh(np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.8, 0.7]]),
...                       np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))
>>> mesh.smooth(passes=2, finish=0)
Report(new, rules, 2 passes, 0 inverted)

In a notebook (with ``anywidget``): ``Playground(points, cells, fixed=None)`` shows a
mesh smoothed two ways side by side, the page's own engine and controls in a cell;
``Playground.from_meshio(mesh)``, ``Playground(sample=NAME)`` and
``Playground(figure=NAME)`` open a meshio mesh, a sample of the gallery or a figure of the
papers' tour. After Step or Run in the widget, ``w.mesh_a`` and ``w.mesh_b`` are each
side's :class:`Mesh`.
"""

from typing import Any

from ._native import __version__
from .mesh import Mesh, Report, read, render, settings, write

__all__ = ["Mesh", "Playground", "Report", "__version__", "figures", "read", "render", "samples", "settings", "write"]


def __getattr__(name: str) -> Any:
    # the widget needs anywidget, which the headless calls do not: imported when asked for
    if name in ("Playground", "samples", "figures"):
        from . import widget

        return getattr(widget, name)
    raise AttributeError(f"module 'smoothlab' has no attribute {name!r}")
