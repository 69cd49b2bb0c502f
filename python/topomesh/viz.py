"""Rendering helpers shared by :meth:`Mesh.plot`, the rich display in Jupyter,
:func:`topomesh.explore`, the gallery and the notebooks.

Surfaces are drawn as their polygon faces (``mesh.padded_faces``; VTK
triangulates them only to shade) and edges as the polygon edges
(``mesh.edges``), never the triangulation's. The camera is fitted to the
mesh's points seen from the view direction (parallel projection), so a render
is filled by the object whatever its proportions. pyvista, IPython and PIL are
imported only when something is drawn.
"""

from __future__ import annotations

import html
import io
import os
import sys
from typing import Any, Iterable, Sequence

import numpy as np

from topomesh._core import Mesh, MeshError

#: colour schemes :func:`scalars` knows by name
COLOR_BY = ("face_size", "valence", "component")
SURFACE = "#d9b38c"
EDGE = "#4d3319"
BACKGROUND = "white"
#: direction to the camera (z up): off the diagonals, so that no face of a
#: regular solid is seen edge-on or face-on
VIEW = (1.0, -1.8, 0.9)
#: meshes with more faces get no inline render in ``_repr_html_``
HTML_RENDER_MAX_FACES = 20_000
#: renders of more faces (in all panels) are not antialiased
ANTIALIAS_MAX_FACES = 50_000
_PLOT_OPTIONS = ("color_by", "edges", "notebook", "screenshot", "off_screen", "window_size", "title", "color", "view")


def _pyvista() -> Any:
    # headless Linux: VTK must pick EGL before it is first imported
    if sys.platform.startswith("linux") and not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    try:
        import pyvista as pv
    except ImportError as e:
        raise ImportError("pyvista is needed to render: pip install 'topomesh[interop]'") from e
    return pv


# ----------------------------------------------------------------- geometry


def surface(mesh: Mesh, triangles: bool = False) -> Any:
    """``pyvista.PolyData`` of the polygon faces (hole faces are not drawn).

    With ``triangles=True`` the faces are :meth:`Mesh.triangulate`'s
    triangles and points (non-convex faces triangulated in their plane, which
    VTK's own fan would not do); per-face colours still follow the source
    faces."""
    pv = _pyvista()
    if triangles:
        verts, t, _ = mesh.triangulate()
        return pv.PolyData.from_regular_faces(verts, t)
    return pv.PolyData(mesh.vertices, mesh.padded_faces)


def edge_lines(mesh: Mesh) -> Any:
    """``pyvista.PolyData`` of the polygon edges as lines (self-loops, of zero
    length, draw nothing)."""
    pv = _pyvista()
    e = mesh.edges
    return pv.PolyData(mesh.vertices, lines=np.c_[np.full(len(e), 2), e].ravel())


def face_components(mesh: Mesh) -> np.ndarray:
    """Component label of every exported face, int64 (``len(face_sizes)``,)."""
    sizes = mesh.face_sizes
    first = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int64)
    return mesh._vertex_components()[mesh.face_indices[first]] if len(sizes) else np.zeros(0, np.int64)


def valences(mesh: Mesh) -> np.ndarray:
    """Valence of every vertex, int64 (V,); a self-loop counts twice."""
    return np.bincount(mesh.edges.ravel(), minlength=mesh.n_vertices).astype(np.int64)


def scalars(mesh: Mesh, color_by: Any) -> tuple[np.ndarray, str, str] | None:
    """``(values, "cell" | "point", label)`` for ``color_by``, or None.

    Raises
    ------
    MeshError
        If ``color_by`` is an unknown name or an array of the wrong length.
    """
    if color_by is None:
        return None
    if isinstance(color_by, str):
        if color_by == "face_size":
            return mesh.face_sizes, "cell", "face size"
        if color_by == "valence":
            return valences(mesh), "point", "valence"
        if color_by == "component":
            return face_components(mesh), "cell", "component"
        raise MeshError(f"color_by = {color_by!r}: expected None, one of {', '.join(map(repr, COLOR_BY))} or an array")
    try:
        a = np.asarray(color_by, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise MeshError(f"color_by: not a name or a numeric array ({e})") from None
    nf, nv = len(mesh.face_sizes), mesh.n_vertices
    if a.ndim != 1 or len(a) not in (nf, nv):
        raise MeshError(f"color_by: an array needs shape ({nf},) (one value per face) or ({nv},) (per vertex), got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise MeshError("color_by: the array has NaN or infinite values")
    return a, ("cell" if len(a) == nf else "point"), "value"


def title_text(mesh: Mesh, label: str = "") -> str:
    """``label`` over ``V=.. E=.. F=.. genus=..``."""
    counts = f"V={mesh.n_vertices} E={mesh.n_edges} F={mesh.n_faces} genus={mesh.genus}"
    return f"{label}\n{counts}" if label else counts


# ------------------------------------------------------------------- camera


def _view_axes(view: Sequence[float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    d = np.asarray(view, dtype=np.float64)
    d = d / np.linalg.norm(d)
    up = np.array([0.0, 0.0, 1.0]) if abs(d[2]) < 0.99 else np.array([0.0, 1.0, 0.0])
    right = np.cross(up, d)
    right /= np.linalg.norm(right)
    return d, right, np.cross(d, right)


def frame(
    plotter: Any, points: np.ndarray, view: Sequence[float] = VIEW, top_margin: float = 0.0, fill: float = 0.92, bottom_margin: float = 0.0
) -> None:
    """Point the active camera of ``plotter`` along ``-view`` at ``points``
    with a parallel projection whose extent is the points' projected
    bounding box: the object fills ``fill`` of the limiting side, centred in
    the image between a band of ``top_margin`` (a fraction of the height,
    for a title) and one of ``bottom_margin`` (for a colour bar)."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if len(pts) > 200_000:  # the extent of a regular sample is the same within a pixel
        pts = pts[:: len(pts) // 100_000]
    if not len(pts):
        pts = np.zeros((1, 3))
    d, right, up = _view_axes(view)
    x, y, z = pts @ right, pts @ up, pts @ d
    cx, cy = (x.min() + x.max()) / 2, (y.min() + y.max()) / 2
    half_w, half_h = max((x.max() - x.min()) / 2, 1e-9), max((y.max() - y.min()) / 2, 1e-9)
    w, h = plotter.window_size
    shape = getattr(plotter, "shape", (1, 1))
    aspect = (w / shape[1]) / (h / shape[0])
    usable = fill * (1.0 - top_margin - bottom_margin)
    scale = max(half_h / usable, half_w / (fill * aspect))  # parallel_scale = half the visible height
    # shift the centre so that the object sits between the bands
    cy += scale * (top_margin - bottom_margin)
    focal = cx * right + cy * up + (z.min() + z.max()) / 2 * d
    depth = max(z.max() - z.min(), half_w, half_h)
    cam = plotter.camera
    cam.parallel_projection = True
    cam.focal_point = focal
    cam.position = focal + d * (4.0 * depth + 1.0)
    cam.up = up
    cam.parallel_scale = scale
    plotter.renderer.ResetCameraClippingRange()


# ---------------------------------------------------------------- rendering


def add(
    plotter: Any,
    mesh: Mesh,
    color_by: Any = None,
    edges: bool | None = True,
    title: bool | str = True,
    color: str = SURFACE,
    name: str = "",
    triangles: bool = False,
) -> None:
    """Add ``mesh`` to the active subplot of ``plotter``: faces, polygon
    edges (``edges=None``: only below 20k faces), colouring and a title
    (True: the counts, a string: that text, False: none). ``name`` makes a
    second call replace the first one's actors."""
    s = scalars(mesh, color_by)
    poly = surface(mesh, triangles)
    if s is not None and s[1] == "cell" and triangles:
        s = (np.asarray(s[0])[mesh.triangulate()[2]], "cell", s[2])
    # render=False: one render at the screenshot, not one per actor. Back
    # faces of a closed, outward-oriented mesh are hidden anyway: culling them
    # halves the software rasterizer's work (not with holes: the inside shows)
    kw: dict[str, Any] = {"name": f"{name}surface", "smooth_shading": False, "show_edges": False, "render": False}
    kw["culling"] = "back" if mesh.n_holes == 0 else None
    if s is None:
        kw["color"] = color
    else:
        values, where, label = s
        (poly.cell_data if where == "cell" else poly.point_data)[label] = values
        bar = {"title": label, "vertical": False, "position_x": 0.25, "position_y": 0.02, "width": 0.5, "height": 0.08,
               "color": "black", "title_font_size": 12, "label_font_size": 10}
        if np.issubdtype(np.asarray(values).dtype, np.integer):
            bar["fmt"] = "%.0f"
            if np.ptp(values) <= 12:
                kw["categories"] = True
                kw["n_colors"] = max(int(np.ptp(values)) + 1, 2)
                bar["n_labels"] = kw["n_colors"]
        kw.update(scalars=label, cmap="viridis", show_scalar_bar=True, scalar_bar_args=bar)
    plotter.add_mesh(poly, **kw)
    if edges is None:
        edges = mesh.n_faces < HTML_RENDER_MAX_FACES
    if edges and mesh.n_edges:
        plotter.add_mesh(edge_lines(mesh), color=EDGE, line_width=1, name=f"{name}edges", render=False)
    elif name:
        plotter.remove_actor(f"{name}edges", render=False)
    if title:
        plotter.add_text(title if isinstance(title, str) else title_text(mesh), font_size=9, name=f"{name}title", color="black", render=False)
    elif name:
        plotter.remove_actor(f"{name}title", render=False)


def _png(image: np.ndarray) -> bytes:
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(image)).save(buf, format="PNG", compress_level=1)
    return buf.getvalue()


def _window_size(window_size: Any) -> tuple[int, int]:
    try:
        w, h = (int(x) for x in window_size)
    except (TypeError, ValueError):
        raise MeshError(f"window_size = {window_size!r}: expected two positive integers (width, height)") from None
    if w <= 0 or h <= 0 or w > 8192 or h > 8192:
        raise MeshError(f"window_size = {window_size!r}: width and height must be in 1..8192")
    return w, h


class Renderer:
    """One off-screen plotter reused for many renders (an interactive
    explorer re-renders on every slider change; making a plotter costs more
    than drawing a small mesh). ``panels`` subplots side by side, their
    cameras linked and fitted to all meshes together."""

    def __init__(self, panels: int = 1, window_size: tuple[int, int] = (640, 480), antialias: bool = True) -> None:
        pv = _pyvista()
        self.panels = panels
        self.plotter = pv.Plotter(shape=(1, panels), off_screen=True, window_size=list(window_size), border=False)
        # pyvista's default 8× MSAA costs 4-7× the render time of a 100k-face
        # mesh in software OpenGL (llvmpipe); 4× where meshes are small, none for large ones
        self.plotter.render_window.SetMultiSamples(4 if antialias else 0)
        self.plotter.set_background(BACKGROUND)
        if panels > 1:
            self.plotter.link_views()

    def render(
        self,
        meshes: Sequence[Mesh],
        titles: Sequence[bool | str] | None = None,
        color_by: Any = None,
        edges: bool | None = True,
        color: str = SURFACE,
        view: Sequence[float] = VIEW,
        triangles: bool = False,
    ) -> bytes:
        """PNG bytes of ``meshes`` (one per panel)."""
        if len(meshes) != self.panels:
            raise MeshError(f"render: {len(meshes)} meshes for {self.panels} panels")
        titles = list(titles) if titles is not None else [True] * self.panels
        for k, m in enumerate(meshes):
            self.plotter.subplot(0, k)
            add(self.plotter, m, color_by=color_by, edges=edges, title=titles[k], color=color, name="p", triangles=triangles)
        pts = np.concatenate([m.vertices for m in meshes]) if meshes else np.zeros((0, 3))
        has_title = any(bool(t) for t in titles)
        for k in range(self.panels):
            self.plotter.subplot(0, k)
            frame(self.plotter, pts, view=view, top_margin=0.12 if has_title else 0.0, bottom_margin=0.14 if color_by is not None else 0.0)
        self.plotter.render()
        return _png(self.plotter.screenshot(return_img=True))

    def close(self) -> None:
        self.plotter.close()


def render_png(
    meshes: Mesh | Sequence[Mesh],
    titles: Sequence[bool | str] | None = None,
    window_size: tuple[int, int] | None = None,
    link: bool = True,
    **kw: Any,
) -> bytes:
    """Off-screen PNG bytes of one mesh or a row of meshes.

    With ``link=True`` every panel has the same camera (fitted to all meshes
    together: sizes compare); with ``link=False`` each is fitted to its own.
    Keywords go to :meth:`Renderer.render` (``color_by``, ``edges``, ``color``, ``view``, ``triangles``).
    """
    row = [meshes] if isinstance(meshes, Mesh) else list(meshes)
    if not row:
        raise MeshError("render_png: no mesh to draw")
    size = _window_size(window_size) if window_size is not None else (640 if len(row) == 1 else 300 * len(row), 480 if len(row) == 1 else 260)
    small = sum(m.n_faces for m in row) <= ANTIALIAS_MAX_FACES
    if link or len(row) == 1:
        r = Renderer(len(row), size, antialias=small)
        try:
            return r.render(row, titles, **kw)
        finally:
            r.close()
    # independent cameras: render each panel alone and paste them
    w = size[0] // len(row)
    tiles = []
    for k, m in enumerate(row):
        r = Renderer(1, (w, size[1]), antialias=small)
        try:
            tiles.append(_decode(r.render([m], [titles[k]] if titles is not None else None, **kw)))
        finally:
            r.close()
    return _png(np.concatenate(tiles, axis=1))


def _decode(png: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))


def show_row(
    meshes: Sequence[Mesh],
    titles: Sequence[str] | None = None,
    color: str = SURFACE,
    edges: bool | None = True,
    size: tuple[int, int] | None = None,
    link: bool = True,
    counts: bool = False,
    **kw: Any,
) -> Any:
    """Show a row of meshes as one static PNG: displayed in a notebook
    (returns None), else returned as an ``IPython.display.Image``.
    ``titles`` label the panels; with ``counts=True`` V, E, F and genus are
    added under each label. Other keywords as in :func:`render_png`."""
    labels: list[bool | str]
    if titles is None:
        labels = [True] * len(meshes) if counts else [False] * len(meshes)
    else:
        labels = [title_text(m, t) if counts else (t or False) for m, t in zip(meshes, titles)]
    png = render_png(list(meshes), labels, window_size=size, link=link, color=color, edges=edges, **kw)
    return _show(png)


def _show(png: bytes) -> Any:
    """Display the PNG in a notebook (None), else return it as an Image (or
    bytes without IPython): shown once wherever the call is in a cell."""
    try:
        from IPython.display import Image, display
    except ImportError:
        return png
    img = Image(data=png, format="png")
    if in_kernel():
        display(img)
        return None
    return img


def in_kernel() -> bool:
    """True inside a running Jupyter (IPython kernel) session."""
    ip = sys.modules.get("IPython")
    if ip is None:
        return False
    try:
        shell = ip.get_ipython()
    except Exception:
        return False
    return shell is not None and getattr(shell, "kernel", None) is not None


# --------------------------------------------------------------- Mesh.plot


def plot(mesh: Mesh, **options: Any) -> Any:
    """:meth:`Mesh.plot` (see its docstring for the options)."""
    unknown = sorted(set(options) - set(_PLOT_OPTIONS))
    if unknown:
        raise MeshError(f"plot: unknown option {unknown[0]!r}; options are {', '.join(_PLOT_OPTIONS)}")
    color_by = options.get("color_by")
    scalars(mesh, color_by)  # bad values fail before any window opens
    edges = options.get("edges", True)
    if edges is not None and not isinstance(edges, (bool, np.bool_)):
        raise MeshError(f"plot: edges = {edges!r} must be True, False or None")
    title = options.get("title", True)
    if not isinstance(title, (bool, str)):
        raise MeshError(f"plot: title = {title!r} must be a bool or a string")
    if isinstance(title, str):
        title = title_text(mesh, title)
    size = _window_size(options.get("window_size", (640, 480)))
    view = options.get("view", VIEW)
    try:
        view = tuple(float(x) for x in view)
        assert len(view) == 3 and np.linalg.norm(view) > 0
    except (TypeError, ValueError, AssertionError):
        raise MeshError(f"plot: view = {options.get('view')!r} must be a non-zero 3-vector (direction to the camera)") from None
    color = options.get("color", SURFACE)
    screenshot = options.get("screenshot")
    notebook = options.get("notebook")
    if notebook is None:
        notebook = in_kernel()
    off_screen = options.get("off_screen")
    has_display = not sys.platform.startswith("linux") or bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    if off_screen is None:
        off_screen = screenshot is not None or not has_display
    render_kw = dict(color_by=color_by, edges=edges, color=color, view=view)

    if notebook and not off_screen:
        viewer = _live_viewer(mesh, size, title, render_kw)
        if viewer is not None:
            if screenshot is not None:
                _write(screenshot, render_png(mesh, [title], window_size=size, **render_kw))
            from IPython.display import display

            display(viewer)
            return None
    if off_screen or notebook:
        png = render_png(mesh, [title], window_size=size, **render_kw)
        if screenshot is not None:
            _write(screenshot, png)
        return _show(png) if notebook else _image(png)
    # an interactive window (a script with a display)
    pv = _pyvista()
    pl = pv.Plotter(window_size=list(size))
    pl.set_background(BACKGROUND)
    add(pl, mesh, color_by=color_by, edges=edges, title=title, color=color)
    frame(pl, mesh.vertices, view=view, top_margin=0.12 if title else 0.0, bottom_margin=0.14 if color_by is not None else 0.0)
    pl.show(screenshot=str(screenshot) if screenshot is not None else None)
    return None


def _image(png: bytes) -> Any:
    try:
        from IPython.display import Image
    except ImportError:
        return png
    return Image(data=png, format="png")


def _write(path: Any, png: bytes) -> None:
    with open(os.fspath(path), "wb") as f:
        f.write(png)


def _live_viewer(mesh: Mesh, size: tuple[int, int], title: Any, kw: dict[str, Any]) -> Any:
    """pyvista's Jupyter viewer (trame) when that backend is chosen and
    works here; None to fall back to a static PNG."""
    pv = _pyvista()
    backend = getattr(pv.global_theme, "jupyter_backend", "static")
    if backend in (None, "static", "none"):
        return None
    try:
        pl = pv.Plotter(window_size=list(size), notebook=True)
        pl.set_background(BACKGROUND)
        add(pl, mesh, color_by=kw["color_by"], edges=kw["edges"], title=title, color=kw["color"])
        frame(pl, mesh.vertices, view=kw["view"], top_margin=0.12 if title else 0.0, bottom_margin=0.14 if kw["color_by"] is not None else 0.0)
        return pl.show(jupyter_backend=backend, return_viewer=True)
    except Exception:  # no trame, no GPU, no kernel comm: the static image is shown instead
        return None


# ------------------------------------------------------- Jupyter rich display

_CAN_RENDER: bool | None = None
_THUMBS: Renderer | None = None


def can_render() -> bool:
    """Whether pyvista renders off-screen here: False once a thumbnail
    render has failed (or pyvista is missing), so later reprs skip it."""
    global _CAN_RENDER
    if _CAN_RENDER is None:
        try:
            _pyvista()
        except ImportError:
            _CAN_RENDER = False
    return _CAN_RENDER is not False


def repr_png(mesh: Mesh) -> bytes | None:
    """A 320×240 PNG thumbnail, or None where pyvista cannot render."""
    global _CAN_RENDER
    if not can_render():
        return None
    global _THUMBS
    try:
        # one plotter kept for thumbnails: a new one costs its first render
        # (shader compilation) every time, several times the drawing itself
        if _THUMBS is None:
            _THUMBS = Renderer(1, (320, 240), antialias=True)
        png = _THUMBS.render([mesh], [False], edges=None)
    except Exception:  # no OpenGL here: remember, and let Jupyter fall back
        _CAN_RENDER = False
        return None
    _CAN_RENDER = True
    return png


def _hist(h: dict[int, int], limit: int = 8) -> str:
    items = sorted(h.items())
    shown = ", ".join(f"{k}: {v}" for k, v in items[:limit])
    return shown + (f", … ({len(items) - limit} more)" if len(items) > limit else "")


def repr_html(mesh: Mesh) -> str:
    """The ``_repr_html_`` table; never raises (a failing row or render is
    left out)."""
    rows: list[tuple[str, str]] = []

    def row(label: str, value: Any) -> None:
        try:
            rows.append((label, str(value() if callable(value) else value)))
        except Exception as e:  # a summary must never break the display
            rows.append((label, f"unavailable ({type(e).__name__})"))

    row("V, E, F", lambda: f"{mesh.n_vertices}, {mesh.n_edges}, {mesh.n_faces}")
    row("χ", lambda: mesh.euler_characteristic)

    def genera() -> str:
        g = mesh.component_genera
        per = ", ".join(map(str, g[:10])) + (f", … ({len(g) - 10} more)" if len(g) > 10 else "")
        return f"{mesh.genus} ({len(g)} component{'s' if len(g) != 1 else ''}: {per})"

    row("genus", genera)
    row("boundaries (holes)", lambda: mesh.n_holes)
    row("self-loops", lambda: mesh.n_self_loops)
    row("face sizes", lambda: _hist(mesh.face_size_histogram))
    row("valences", lambda: _hist(mesh.valence_histogram))

    def bbox() -> str:
        v = mesh.vertices
        if not len(v):
            return "empty"
        lo, hi = v.min(axis=0), v.max(axis=0)
        return f"[{', '.join(f'{x:.4g}' for x in lo)}] – [{', '.join(f'{x:.4g}' for x in hi)}]"

    row("bounding box", bbox)
    cells = "".join(
        f"<tr><th style='text-align:left;padding-right:1em'>{html.escape(k)}</th><td style='text-align:left'>{html.escape(v)}</td></tr>"
        for k, v in rows
    )
    table = f"<table><caption style='text-align:left'><b>{html.escape(_safe_repr(mesh))}</b></caption>{cells}</table>"
    img = ""
    try:
        if mesh.n_faces <= HTML_RENDER_MAX_FACES:
            png = repr_png(mesh)
            if png:
                import base64

                img = f"<td style='vertical-align:top'><img src='data:image/png;base64,{base64.b64encode(png).decode()}' width='240'/></td>"
    except Exception:
        img = ""
    return f"<table><tr><td style='vertical-align:top'>{table}</td>{img}</tr></table>"


def _safe_repr(mesh: Mesh) -> str:
    try:
        return repr(mesh)
    except Exception:
        return "Mesh"


def image_row(pngs: Iterable[bytes]) -> bytes:
    """Paste PNGs side by side (same height) into one PNG."""
    tiles = [_decode(p) for p in pngs]
    h = max(t.shape[0] for t in tiles)
    tiles = [np.pad(t, ((0, h - t.shape[0]), (0, 0), (0, 0)), constant_values=255) for t in tiles]
    return _png(np.concatenate(tiles, axis=1))


def render_grid(
    meshes: Sequence[Mesh],
    titles: Sequence[str] | None = None,
    cols: int = 8,
    panel: tuple[int, int] = (120, 110),
    edges: bool | None = True,
    color: str = SURFACE,
    view: Sequence[float] = VIEW,
) -> bytes:
    """PNG bytes of small multiples: ``meshes`` in a grid of ``cols``
    columns, each panel ``panel`` pixels and fitted to its own mesh, drawn
    in one off-screen window (one render for the whole grid: a catalog of a
    hundred thumbnails costs seconds, not a plotter each)."""
    if not meshes:
        raise MeshError("render_grid: no mesh to draw")
    if cols < 1:
        raise MeshError(f"render_grid: cols = {cols}; expected at least 1")
    pv = _pyvista()
    cols = min(cols, len(meshes))
    rows = -(-len(meshes) // cols)
    w, h = _window_size(panel)
    plotter = pv.Plotter(shape=(rows, cols), off_screen=True, window_size=[cols * w, rows * h], border=False)
    try:
        # no antialiasing: software OpenGL pays it per pixel of the whole grid
        plotter.render_window.SetMultiSamples(0)
        plotter.set_background(BACKGROUND)
        for k, m in enumerate(meshes):
            plotter.subplot(k // cols, k % cols)
            label = titles[k] if titles is not None else ""
            add(plotter, m, edges=edges, title=False, color=color)
            if label:
                # a fixed-size text actor: a corner annotation scales its font with the label's length
                plotter.add_text(label, position=(0.03, 0.87), viewport=True, font_size=7, color="black", render=False)
            frame(plotter, m.vertices, view=view, top_margin=0.16 if label else 0.0)
        plotter.render()
        return _png(plotter.screenshot(return_img=True))
    finally:
        plotter.close()


def show_grid(meshes: Sequence[Mesh], titles: Sequence[str] | None = None, **kw: Any) -> Any:
    """:func:`render_grid`, shown as one static PNG (in a notebook: displayed,
    returns None; else an ``IPython.display.Image``)."""
    return _show(render_grid(meshes, titles, **kw))
