"""The widget: the playground page in a notebook cell (anywidget).

Its ES module (``static/widget.js``) is the bridge between this model and the page
(python/widget/widget.js); the page (``static/page.html.gz``, the one-file page, its wasm
inside, gzipped) is the state of one model that every widget of the kernel shares, so a notebook
saved with its widgets' state holds it once. Both are built by ``make python``;
``static/sheet.json`` is what the arguments are checked against: the page's control
sheet, samples and tour figures, read from the same wasm module by the same build, so
nothing here repeats them.
"""

from __future__ import annotations

import base64
import json
import pathlib
import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

try:
    import anywidget
except ImportError:
    raise ImportError("smoothlab's notebook widget needs anywidget: pip install anywidget") from None
import ipywidgets
import numpy as np
import traitlets

from .mesh import Mesh, check_cells, check_fixed, check_points, render, vtk_text

STATIC = pathlib.Path(__file__).parent / "static"
MODULE = STATIC / "widget.js"
PAGE_FILE = STATIC / "page.html.gz"
SHEET_FILE = STATIC / "sheet.json"
if not (MODULE.is_file() and PAGE_FILE.is_file() and SHEET_FILE.is_file()):
    raise ImportError(
        "smoothlab's widget module is not in this install: build the wheel with `make wheel` in the "
        "smoothlab repository, then pip install target/wheels/smoothlab-*.whl again"
    )
SHEET = json.loads(SHEET_FILE.read_text(encoding="utf-8"))


def samples() -> List[str]:
    """The names of the gallery's samples, for ``Playground(sample=NAME)``."""
    return [s["name"] for s in SHEET["samples"]]


def figures() -> List[str]:
    """The names of the tour's figures, for ``Playground(figure=NAME)``."""
    return [f["name"] for f in SHEET["figures"]]


def _menu(name: str) -> List[Any]:
    """What the page's menu for a setting offers (its values as the page holds them)."""
    c = SHEET["controls"]
    return {
        "strategy": [s["name"] for s in c["strategies"]],
        "order": [o["name"] for o in c["orders"]],
        "threshold": c["threshold"]["options"],
        "objective_a": [o["name"] for o in c["objectives"]],
        "objective_b": [o["name"] for o in c["objectives"]],
        "penalty_a": [p["name"] for p in c["penalties"]],
        "penalty_b": [p["name"] for p in c["penalties"]],
    }[name]


def _range(name: str) -> Dict[str, Any]:
    """A typed setting's control: its label, limits and the limits in words."""
    return SHEET["controls"]["maxiter" if name == "max_iter" else name]


class _Page(ipywidgets.Widget):
    """The one-file page every :class:`Playground` of the kernel shows: a model with no view
    of its own, sent to the browser once and saved once in a notebook's widget state: the
    page gzipped (1.3 MB) in base64 (1.8 MB), text, which every widget manager saves as it
    is (a base model's bytes are not saved)."""

    page = traitlets.Unicode("").tag(sync=True)


_SHARED: Optional[_Page] = None


def _shared_page() -> _Page:
    """The kernel's one page model, made on first use (again if it was closed)."""
    global _SHARED
    if _SHARED is None or getattr(_SHARED, "comm", None) is None:
        _SHARED = _Page(page=base64.b64encode(PAGE_FILE.read_bytes()).decode("ascii"))
    return _SHARED


class Playground(anywidget.AnyWidget):
    """Two smoothers side by side on one mesh, the playground page in a notebook cell.

    ``Playground(points, cells, fixed=None)``: a mesh as arrays (see :mod:`smoothlab.mesh`);
    ``Playground(sample=NAME)``: a sample of the gallery (:func:`samples`);
    ``Playground(figure=NAME)``: one figure of the papers' tour (:func:`figures`);
    :meth:`from_meshio`: a meshio mesh. Settings are keyword arguments and traits
    (``strategy``, ``threshold``, ``order``, ``passes``, ``max_iter``, ``objective_a``,
    ``penalty_a``, ``objective_b``, ``penalty_b``; None: the page's default, filled in
    once the widget is shown). ``mesh_a`` and ``mesh_b`` are the sides' meshes as the page
    last reported them, ``stats`` their tables, ``error`` what the page refused.
    ``sample`` and ``figure`` may be assigned after the widget is shown, and
    :meth:`set_mesh` gives it another mesh: the view opens it anew. A mesh in 3D is seen
    by ``camera`` (yaw and pitch in degrees, and a zoom: ``(30, 25, 1)``) and a volume cut
    by ``cut`` (an axis and a fraction of its extent: ``("z", 0.5)``), as
    :func:`smoothlab.render` takes them; both are set at first and whenever assigned, and
    follow the view as it is turned (None: the page's own, filled in once shown).

    >>> import smoothlab
    >>> w = smoothlab.Playground(sample="plate-tri-tangled", passes=3)
    >>> w.figure = "chen-10"
    >>> w.sample is None, w.figure
    (True, 'chen-10')
    """

    _esm = MODULE

    _page = traitlets.Instance(_Page).tag(sync=True, **ipywidgets.widget_serialization)
    _file = traitlets.Bytes(b"").tag(sync=True)
    _file_name = traitlets.Unicode("").tag(sync=True)
    sample = traitlets.Unicode(None, allow_none=True).tag(sync=True)
    figure = traitlets.Unicode(None, allow_none=True).tag(sync=True)
    height = traitlets.Int(540).tag(sync=True)

    strategy = traitlets.Unicode(None, allow_none=True).tag(sync=True)
    threshold = traitlets.Float(None, allow_none=True).tag(sync=True)
    order = traitlets.Unicode(None, allow_none=True).tag(sync=True)
    passes = traitlets.Int(None, allow_none=True).tag(sync=True)
    max_iter = traitlets.Int(None, allow_none=True).tag(sync=True)
    objective_a = traitlets.Unicode(None, allow_none=True).tag(sync=True)
    penalty_a = traitlets.Unicode(None, allow_none=True).tag(sync=True)
    objective_b = traitlets.Unicode(None, allow_none=True).tag(sync=True)
    penalty_b = traitlets.Unicode(None, allow_none=True).tag(sync=True)

    camera = traitlets.Any(None, allow_none=True).tag(sync=True)
    cut = traitlets.Any(None, allow_none=True).tag(sync=True)

    _mesh_a = traitlets.Dict({}).tag(sync=True)
    _mesh_b = traitlets.Dict({}).tag(sync=True)
    stats = traitlets.Dict({}).tag(sync=True)
    error = traitlets.Unicode(None, allow_none=True).tag(sync=True)

    SETTINGS = ("strategy", "threshold", "order", "passes", "max_iter", "objective_a", "penalty_a", "objective_b", "penalty_b")

    def __init__(
        self,
        points: Any = None,
        cells: Any = None,
        fixed: Any = None,
        *,
        sample: Optional[str] = None,
        figure: Optional[str] = None,
        height: int = 540,
        camera: Any = None,
        cut: Any = None,
        **settings: Any,
    ):
        given = [what for what, v in (("points and cells", points if points is not None else cells), ("sample", sample), ("figure", figure)) if v is not None]
        if len(given) > 1:
            raise ValueError(f"give one of points and cells, sample or figure, not {' and '.join(given)}")
        unknown = sorted(set(settings) - set(self.SETTINGS))
        if unknown:
            raise TypeError(f"no setting named {', '.join(map(repr, unknown))}: the settings are {', '.join(self.SETTINGS)}")
        init: Dict[str, Any] = {"height": height, "_page": _shared_page(), "camera": camera, "cut": cut}
        self._given: Optional[Mesh] = None
        if points is not None or cells is not None:
            if points is None or cells is None:
                raise ValueError("give both points and cells (or a sample or a figure)")
            p = check_points(points)
            c = check_cells(cells, len(p), p)
            f = check_fixed(fixed, len(p))
            init["_file"] = vtk_text(p, c, f).encode("utf-8")
            init["_file_name"] = "notebook.vtk"
            self._given = Mesh(p, c, f)
        elif fixed is not None:
            raise ValueError("fixed goes with points and cells: a sample or a figure fixes its own nodes")
        elif sample is not None:
            if sample not in samples():
                raise ValueError(f"no sample named {sample!r}; the samples are {', '.join(samples())}")
            init["sample"] = sample
        elif figure is not None:
            if figure not in figures():
                raise ValueError(f"no figure named {figure!r}; the figures are {', '.join(figures())}")
            init["figure"] = figure
        else:
            raise ValueError("give a mesh (points and cells), a sample or a figure")
        self._made = False  # the view given with the mesh is not let go while it is made
        super().__init__(**init, **settings)
        self._made = True
        self.on_msg(self._on_message)

    def _on_message(self, widget: Any, content: Any, buffers: Any) -> None:
        """The view asks for the page by a message where its front end cannot reach the
        shared page model (``widget_manager.get_model``): the answer is kept in no state."""
        if isinstance(content, dict) and content.get("smoothlab") == "page?":
            self.send({"smoothlab": "page", "page": self._page.page})

    @classmethod
    def from_meshio(cls, mesh: Any, fixed: Any = None, **kwargs: Any) -> "Playground":
        """A playground on a meshio mesh: its points and cell blocks; its point data
        ``fixed`` (as smoothlab writes it) fixes nodes when ``fixed`` is not given."""
        if not (hasattr(mesh, "points") and hasattr(mesh, "cells")):
            raise TypeError(f"from_meshio takes a meshio.Mesh, not {type(mesh).__name__}")
        if fixed is None and "fixed" in getattr(mesh, "point_data", {}):
            fixed = np.asarray(mesh.point_data["fixed"]).reshape(-1) != 0
        return cls(mesh.points, list(mesh.cells), fixed, **kwargs)

    def set_mesh(self, points: Any, cells: Any, fixed: Any = None) -> None:
        """Shows another mesh, given as :class:`Playground` takes one (a shown widget
        opens it anew); the sample or figure it showed is let go."""
        p = check_points(points)
        c = check_cells(cells, len(p), p)
        f = check_fixed(fixed, len(p))
        given = Mesh(p, c, f)
        with self.hold_sync():
            self.sample = None
            self.figure = None
            self.camera = None
            self.cut = None
            self._file_name = "notebook.vtk"
            self._file = vtk_text(p, c, f).encode("utf-8")
            self._mesh_a = {}
            self._mesh_b = {}
            self.stats = {}
            self.error = None
        self._given = given

    @traitlets.validate("sample", "figure")
    def _check_name(self, proposal: Any) -> Any:
        v, name = proposal["value"], proposal["trait"].name
        names = samples() if name == "sample" else figures()
        if v is not None and v not in names:
            raise traitlets.TraitError(f"{name}: no {name} named {v!r}; the {name}s are {', '.join(names)}")
        return v

    @traitlets.observe("sample", "figure")
    def _open_by_name(self, change: Any) -> None:
        """A sample or a figure assigned after the widget is made (shown or not) replaces
        what it showed: the other name, the mesh given as arrays and the sides' meshes
        and tables as last reported are let go, and the view opens it anew."""
        if change["new"] is None:
            return
        other = "figure" if change["name"] == "sample" else "sample"
        self._given = None
        with self.hold_sync():
            setattr(self, other, None)
            if self._made:
                self.camera = None
                self.cut = None
            self._file = b""
            self._file_name = ""
            self._mesh_a = {}
            self._mesh_b = {}
            self.stats = {}
            self.error = None

    @traitlets.validate("camera")
    def _check_camera(self, proposal: Any) -> Any:
        v = proposal["value"]
        if v is None:
            return None
        try:
            c = [float(x) for x in v]
        except (TypeError, ValueError):
            raise traitlets.TraitError(f"camera: give (yaw, pitch) or (yaw, pitch, zoom) in numbers, not {v!r}") from None
        if len(c) not in (2, 3) or not all(np.isfinite(c)):
            raise traitlets.TraitError(f"camera: give (yaw, pitch) or (yaw, pitch, zoom) in finite numbers, not {v!r}")
        if len(c) == 2:
            c.append(1.0)
        if c[2] <= 0:
            raise traitlets.TraitError(f"camera: the zoom {c[2]} is not positive")
        return c

    @traitlets.validate("cut")
    def _check_cut(self, proposal: Any) -> Any:
        v = proposal["value"]
        if v is None:
            return None
        try:
            axis, at = v
            at = float(at)
        except (TypeError, ValueError):
            raise traitlets.TraitError(f"cut: give (axis, fraction) such as ('z', 0.5), not {v!r}") from None
        if axis not in ("x", "y", "z"):
            raise traitlets.TraitError(f"cut: the axis is 'x', 'y' or 'z', not {axis!r}")
        if not 0 <= at <= 1:
            raise traitlets.TraitError(f"cut: the fraction {at} is not between 0 and 1")
        return [axis, at]

    @traitlets.validate("strategy", "order", "threshold", "objective_a", "penalty_a", "objective_b", "penalty_b")
    def _check_menu(self, proposal: Any) -> Any:
        v, name = proposal["value"], proposal["trait"].name
        offered = _menu(name)
        if v is not None and v not in offered:
            raise traitlets.TraitError(f"{name}: {v!r} is not offered; choose one of {', '.join(map(str, offered))}")
        return v

    @traitlets.validate("passes", "max_iter")
    def _check_range(self, proposal: Any) -> Any:
        v, name = proposal["value"], proposal["trait"].name
        r = _range(name)
        if v is not None and not int(r["min"]) <= v <= int(r["max"]):
            raise traitlets.TraitError(f"{name}: {v} is out of range; {r['label']}: {r['words']}")
        return v

    def _side(self, trait: str, letter: str) -> Mesh:
        state = getattr(self, trait)
        if state:
            # the page gives a mesh in the xy plane two coordinates; points given with three
            # (meshio's, z = 0) come back with three
            given_3d = self._given is not None and self._given.points.shape[1] == 3
            return Mesh.from_page(state, dim=3 if given_3d else None)
        if self._given is not None:
            return self._given
        raise RuntimeError(
            f"side {letter}'s mesh is made by the page: show the widget (its cell's output) first, then read mesh_{letter.lower()}"
        )

    @property
    def mesh_a(self) -> Mesh:
        """Side A's mesh as the page last reported it (after a Step, a Run, a drag, a
        Reset); the mesh as given before the page has reported one."""
        return self._side("_mesh_a", "A")

    @property
    def mesh_b(self) -> Mesh:
        """Side B's mesh, as :attr:`mesh_a`."""
        return self._side("_mesh_b", "B")

    def save_png(
        self,
        path: Union[str, "os.PathLike[str]"],
        side: str = "b",
        *,
        size: Optional[Tuple[int, int]] = None,
        dpr: Optional[float] = None,
        metric: Optional[str] = None,
        theme: Optional[str] = None,
        camera: Union[None, str, Sequence[float]] = None,
        cut: Union[None, str, Tuple[str, float]] = None,
    ) -> None:
        """Draws side ``"a"`` or ``"b"`` (B, the new objective's, by default) as the page
        last reported it (:attr:`mesh_a`, :attr:`mesh_b`) to a PNG file, as
        :func:`smoothlab.render` draws it with ``view="mesh"``, in the kernel: the widget
        need not be on screen (before the page has reported, the mesh as given). ``size``, ``dpr``, ``metric``,
        ``theme``, ``camera`` and ``cut`` as for :func:`smoothlab.render`; ``camera`` and
        ``cut`` left out are the widget's (its view as last turned).

        >>> import pathlib, tempfile, numpy as np, smoothlab
        >>> w = smoothlab.Playground(np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.8, 0.7]]), np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]))
        >>> out = pathlib.Path(tempfile.mkdtemp()) / "b.png"
        >>> w.save_png(out, size=(300, 300))
        >>> out.read_bytes()[:4]
        b'\\x89PNG'
        """
        if side not in ("a", "b"):
            raise ValueError(f"side: 'a' or 'b', not {side!r}")
        mesh = self.mesh_a if side == "a" else self.mesh_b
        camera = self.camera if camera is None else camera
        cut = self.cut if cut is None else cut
        render(mesh, path, "mesh", size=size, dpr=dpr, metric=metric, theme=theme, camera=camera, cut=cut)
