"""smoothlab in a notebook: the playground page as a widget (anywidget).

``Playground(points, cells, fixed=None)`` shows a mesh smoothed two ways side by side, the
page's own engine and controls in a notebook cell; ``Playground.from_meshio(mesh)``,
``Playground(sample=NAME)`` and ``Playground(figure=NAME)`` open a meshio mesh, a sample of
the gallery or a figure of the papers' tour. After Step or Run in the widget,
``w.mesh_a`` and ``w.mesh_b`` are each side's mesh as NumPy arrays (``to_meshio()`` too).
"""

from .mesh import Mesh
from .widget import Playground, figures, samples

__all__ = ["Mesh", "Playground", "figures", "samples"]
