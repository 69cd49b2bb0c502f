"""Live parameters in Jupyter: :func:`explore` puts a scheme's parameters on
ipywidgets sliders, re-runs the Rust scheme on every change and re-renders
off-screen into an ``ipywidgets.Image`` (works headless, with no GPU and no
browser-side 3D). Without ipywidgets it shows a static row of renders.
"""

from __future__ import annotations

import time
import warnings
from collections import OrderedDict
from typing import Any, Mapping, Sequence

from topomesh import viz
from topomesh._core import Mesh, MeshError

#: scheme -> {parameter: (default, default range)}; a range is (lo, hi, step)
#: for a slider or a list for a dropdown. A default of None (honeycomb's
#: per-face tension) gets a widget only when a range is passed.
SCHEMES: dict[str, dict[str, tuple[Any, Any]]] = {
    "catmull_clark": {},
    "doo_sabin": {},
    "loop": {},
    "sqrt3": {},
    "simplest": {},
    "midpoint": {},
    "dual": {},
    "honeycomb": {"t": (0.5, (0.05, 0.95, 0.05)), "tension": (None, (0.05, 1.0, 0.05))},
    "vertex_truncation": {"mode": ("chaikin", ["chaikin", "polyhedral"]), "ratio": (0.25, (0.05, 0.5, 0.01))},
    "sierpinski": {},
    # collapse_angle applies to offset="merged" only: a slider only when a range is passed
    "menger": {"thickness": (1.0 / 3.0, (0.05, 0.45, 0.01)), "offset": ("per_face", ["per_face", "merged"]),
               "collapse_angle": (None, (0.0, 180.0, 5.0))},
}
_CACHE_SIZE = 16


def _widgets() -> Any:
    import ipywidgets

    return ipywidgets


def _check_range(name: str, spec: Any) -> Any:
    """A validated range: ``(lo, hi, step)``, a non-empty list, or a fixed value."""
    if isinstance(spec, list):
        if not spec:
            raise MeshError(f"explore: {name} = []: a dropdown needs at least one value")
        return spec
    if isinstance(spec, tuple):
        if len(spec) not in (2, 3) or not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in spec):
            raise MeshError(f"explore: {name} = {spec!r}: a range is (lo, hi) or (lo, hi, step) of numbers")
        lo, hi = spec[0], spec[1]
        step = spec[2] if len(spec) == 3 else None
        if not lo < hi:
            raise MeshError(f"explore: {name} = {spec!r}: lo must be below hi")
        if step is not None and not 0 < step <= hi - lo:
            raise MeshError(f"explore: {name} = {spec!r}: step must be in (0, hi - lo]")
        if step is None:
            step = 1 if all(isinstance(x, int) for x in (lo, hi)) else (hi - lo) / 50
        return (lo, hi, step)
    return spec


class _Panel:
    """One scheme's controls and its current output."""

    def __init__(self, owner: "Explorer", scheme: str, values: Mapping[str, Any], iterations: Any) -> None:
        self.owner = owner
        self.scheme = scheme
        self.values: dict[str, Any] = {}  # current parameter values, by name (shared across schemes)
        for s in owner.schemes:
            for p, (default, rng) in SCHEMES[s].items():
                spec = owner.ranges.get(p, rng)
                if p in values:
                    self.values[p] = values[p]
                elif p in owner.ranges and not isinstance(spec, (tuple, list)):
                    self.values[p] = spec
                elif default is None and p in owner.ranges:
                    self.values[p] = spec[0] if isinstance(spec, list) else (spec[0] + spec[1]) / 2
                else:
                    self.values.setdefault(p, default)
        self.iter_range = (0, 3, 1)
        if isinstance(iterations, tuple):
            self.iter_range = tuple(int(x) for x in _check_range("iterations", iterations))  # type: ignore[assignment]
            self.iterations = int(values.get("iterations", min(max(1, self.iter_range[0]), self.iter_range[1])))
        else:
            self.iterations = int(values.get("iterations", iterations))
            if self.iterations < 0:
                raise MeshError(f"explore: iterations = {self.iterations} must be >= 0")
            self.iter_range = (0, max(3, self.iterations), 1)
        self.mesh: Mesh | None = None
        self.error = ""
        self.widgets: dict[str, Any] = {}
        self._param_widgets: dict[str, Any] = {}
        self.box: Any = None

    def shown_params(self, scheme: str) -> list[str]:
        return [p for p, (default, _) in SCHEMES[scheme].items() if default is not None or p in self.owner.ranges]

    def kwargs(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for p, (default, _) in SCHEMES[self.scheme].items():
            v = self.values.get(p, default)
            if v is not None:
                out[p] = v
        return out

    def run(self, mesh: Mesh, key: str) -> Mesh:
        kw = self.kwargs()
        cache_key = (key, self.scheme, self.iterations, tuple(sorted(kw.items())))
        cache = self.owner._cache
        if cache_key in cache:
            cache.move_to_end(cache_key)
            return cache[cache_key]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            out = getattr(mesh, self.scheme)(iterations=self.iterations, **kw)
        self.error = "; ".join(str(w.message) for w in caught)
        cache[cache_key] = out
        while len(cache) > _CACHE_SIZE:
            cache.popitem(last=False)
        return out

    # ---------------------------------------------------------- widgets

    def build(self, w: Any) -> None:
        layout = w.Layout(width="320px")
        self.widgets["scheme"] = w.Dropdown(options=list(self.owner.schemes), value=self.scheme, description="scheme", layout=layout)
        lo, hi, step = self.iter_range
        self.widgets["iterations"] = w.IntSlider(
            value=self.iterations, min=lo, max=hi, step=step, description="iterations", continuous_update=False, layout=layout
        )
        self.widgets["scheme"].observe(self._on_scheme, names="value")
        self.widgets["iterations"].observe(self._on_iterations, names="value")
        self.params_box = w.VBox([])
        self.box = w.VBox([self.widgets["scheme"], self.widgets["iterations"], self.params_box])
        self._show_params(w)

    def _param_widget(self, w: Any, p: str) -> Any:
        if p in self._param_widgets:
            return self._param_widgets[p]
        spec = self.owner.ranges.get(p)
        if spec is None:
            spec = next(SCHEMES[s][p][1] for s in self.owner.schemes if p in SCHEMES[s])
        if not isinstance(spec, (tuple, list)):
            return None  # a fixed value: no widget
        layout = w.Layout(width="320px")
        v = self.values[p]
        if isinstance(spec, list):
            widget = w.Dropdown(options=spec, value=v if v in spec else spec[0], description=p, layout=layout)
        else:
            lo, hi, step = spec
            cls = w.IntSlider if all(isinstance(x, int) for x in spec) else w.FloatSlider
            value = min(max(v, lo), hi)
            widget = cls(value=value, min=lo, max=hi, step=step, description=p, continuous_update=False, layout=layout)
            if cls is w.FloatSlider:
                widget.readout_format = ".3g"
        self.values[p] = widget.value
        widget.observe(lambda change, p=p: self._on_param(p, change), names="value")
        self._param_widgets[p] = widget
        return widget

    def _show_params(self, w: Any) -> None:
        for p in list(self.widgets):
            if p not in ("scheme", "iterations"):
                del self.widgets[p]
        shown = []
        for p in self.shown_params(self.scheme):
            widget = self._param_widget(w, p)
            if widget is not None:
                self.widgets[p] = widget
                shown.append(widget)
        self.params_box.children = tuple(shown)

    def _on_scheme(self, change: Mapping[str, Any]) -> None:
        self.scheme = change["new"]
        self._show_params(_widgets())
        self.owner.update()

    def _on_iterations(self, change: Mapping[str, Any]) -> None:
        self.iterations = int(change["new"])
        self.owner.update()

    def _on_param(self, p: str, change: Mapping[str, Any]) -> None:
        self.values[p] = change["new"]
        self.owner.update()


class Explorer:
    """What :func:`explore` returns: the widgets, the current output mesh(es)
    and image, and the time each update took.

    Attributes
    ----------
    widgets : dict of str to ipywidgets.Widget
        The first panel's controls by name (``"scheme"``, ``"iterations"``,
        the scheme's parameters, ``"input"`` for a dict of inputs); empty
        without ipywidgets. Setting a ``.value`` re-runs and re-renders.
    panels : list
        One per side; ``panels[1].widgets`` are the right side's in compare mode.
    image : ipywidgets.Image or IPython.display.Image or bytes
        What is displayed; :attr:`png` is its bytes.
    timings : list of dict
        ``{"scheme": s, "render": s, "faces": F}`` per update (seconds).
    """

    def __init__(
        self,
        mesh: Mesh | Mapping[str, Mesh],
        scheme: str | Sequence[str],
        ranges: dict[str, Any],
        iterations: Any,
        compare: str | Mapping[str, Any] | None,
        window_size: tuple[int, int] | None,
        color_by: Any,
        edges: bool | None,
    ) -> None:
        if isinstance(mesh, Mesh):
            self.inputs: dict[str, Mesh] = {"mesh": mesh}
        elif isinstance(mesh, Mapping) and mesh and all(isinstance(m, Mesh) for m in mesh.values()):
            self.inputs = {str(k): m for k, m in mesh.items()}
        else:
            raise MeshError("explore: mesh must be a Mesh or a non-empty dict of name -> Mesh")
        known = [s for s in SCHEMES if hasattr(Mesh, s)]
        names = [scheme] if isinstance(scheme, str) else list(scheme)
        for s in names:
            if s not in known:
                raise MeshError(f"explore: unknown scheme {s!r}; schemes are {', '.join(known)}")
        if not names:
            raise MeshError("explore: scheme list is empty")
        # a single name selects it in a dropdown of every scheme
        self.schemes = known if isinstance(scheme, str) else names
        all_params = {p for s in self.schemes for p in SCHEMES[s]}
        for p in ranges:
            if p not in all_params:
                raise MeshError(f"explore: {p!r} is not a parameter of {', '.join(self.schemes)}; parameters are {', '.join(sorted(all_params)) or 'none'}")
        self.ranges = {p: _check_range(p, spec) for p, spec in ranges.items()}
        if color_by is not None and color_by not in viz.COLOR_BY:
            # an array would not match the outputs, whose sizes change
            raise MeshError(f"explore: color_by = {color_by!r}: expected None or one of {', '.join(map(repr, viz.COLOR_BY))}")
        self.color_by, self.edges = color_by, edges
        self.input_name = next(iter(self.inputs))
        self._cache: OrderedDict[Any, Mesh] = OrderedDict()
        self.timings: list[dict[str, float]] = []
        self.panels = [_Panel(self, names[0], {}, iterations)]
        if compare is not None:
            if isinstance(compare, str):
                other = {"scheme": compare}
            elif isinstance(compare, Mapping):
                other = dict(compare)
            else:
                raise MeshError(f"explore: compare = {compare!r}: a scheme name or a dict of parameter values")
            s2 = other.pop("scheme", names[0])
            if s2 not in self.schemes:
                raise MeshError(f"explore: compare scheme {s2!r} is not among {', '.join(self.schemes)}")
            bad = sorted(set(other) - all_params - {"iterations"})
            if bad:
                raise MeshError(f"explore: compare parameter {bad[0]!r} is not a parameter of {', '.join(self.schemes)}")
            self.panels.append(_Panel(self, s2, other, iterations))
        n = len(self.panels)
        self.window_size = viz._window_size(window_size) if window_size is not None else (480 * n, 400)
        self._renderer: viz.Renderer | None = None
        self.png = b""
        try:
            w = _widgets()
        except ImportError:
            w = None
        self.interactive = w is not None
        self.status: Any = None
        if w is not None:
            self.image = w.Image(format="png", layout=w.Layout(width=f"{self.window_size[0]}px"))
            self.status = w.HTML("")
            controls = []
            self.input_widget = None
            if len(self.inputs) > 1:
                self.input_widget = w.Dropdown(options=list(self.inputs), value=self.input_name, description="input", layout=w.Layout(width="320px"))
                self.input_widget.observe(self._on_input, names="value")
            for p in self.panels:
                p.build(w)
                controls.append(p.box)
            head = [self.input_widget] if self.input_widget is not None else []
            self.layout = w.VBox([*head, w.HBox(controls), self.image, self.status])
            self.update()
        else:
            self._static()

    # ------------------------------------------------------------ state

    @property
    def widgets(self) -> dict[str, Any]:
        out = dict(self.panels[0].widgets)
        if self.interactive and self.input_widget is not None:
            out["input"] = self.input_widget
        return out

    @property
    def mesh(self) -> Mesh | None:
        """The output of the first (left) panel."""
        return self.panels[0].mesh

    @property
    def meshes(self) -> list[Mesh | None]:
        return [p.mesh for p in self.panels]

    @property
    def input(self) -> Mesh:
        return self.inputs[self.input_name]

    def _on_input(self, change: Mapping[str, Any]) -> None:
        self.input_name = change["new"]
        self.update()

    def _title(self, p: _Panel) -> str:
        kw = ", ".join(f"{k}={v:.3g}" if isinstance(v, float) else f"{k}={v}" for k, v in p.kwargs().items())
        return f"{p.scheme}({p.iterations}{', ' + kw if kw else ''})"

    def update(self) -> None:
        """Re-run every panel's scheme and re-render (the widgets call this)."""
        t0 = time.perf_counter()
        errors = []
        for p in self.panels:
            try:
                p.mesh = p.run(self.input, self.input_name)
                if p.error:
                    errors.append(f"{p.scheme}: {p.error}")
            except (MeshError, ValueError) as e:
                # a bad parameter combination: keep the last good output and say why
                errors.append(f"{p.scheme}: {e}")
                if p.mesh is None:
                    p.mesh = self.input
        t1 = time.perf_counter()
        if self._renderer is None:
            big = max(m.n_faces for m in self.inputs.values()) > viz.HTML_RENDER_MAX_FACES
            self._renderer = viz.Renderer(len(self.panels), self.window_size, antialias=not big)
        meshes = [p.mesh for p in self.panels if p.mesh is not None]
        self.png = self._renderer.render(
            meshes, [viz.title_text(p.mesh, self._title(p)) for p in self.panels if p.mesh is not None], color_by=self.color_by, edges=self.edges
        )
        t2 = time.perf_counter()
        self.timings.append({"scheme": t1 - t0, "render": t2 - t1, "faces": float(sum(m.n_faces for m in meshes))})
        if self.interactive:
            self.image.value = self.png
            self.status.value = "<br>".join(f"<span style='color:#a00'>{_esc(e)}</span>" for e in errors) + (
                f"<small>scheme {1e3 * (t1 - t0):.0f} ms, render {1e3 * (t2 - t1):.0f} ms</small>"
            )
        self.errors = errors

    def _static(self) -> None:
        """No ipywidgets: the input and the scheme at each iteration of the
        range (or each side of a comparison), as one row of PNGs."""
        self.errors = []
        row, titles = [self.input], [viz.title_text(self.input, self.input_name)]
        if len(self.panels) == 1:
            p = self.panels[0]
            lo, hi, _ = p.iter_range
            for k in range(max(1, lo), min(hi, 3) + 1):
                p.iterations = k
                p.mesh = p.run(self.input, self.input_name)
                row.append(p.mesh)
                titles.append(viz.title_text(p.mesh, self._title(p)))
        else:
            for p in self.panels:
                p.mesh = p.run(self.input, self.input_name)
                row.append(p.mesh)
                titles.append(viz.title_text(p.mesh, self._title(p)))
        self.png = viz.render_png(row, titles, window_size=(320 * len(row), 300), link=False, color_by=self.color_by, edges=self.edges)
        self.image = viz._show(self.png)

    def close(self) -> None:
        """Release the off-screen plotter."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.layout if self.interactive else self.image)


def _esc(s: str) -> str:
    import html

    return html.escape(s)


def explore(
    mesh: Mesh | Mapping[str, Mesh],
    scheme: str | Sequence[str] = "catmull_clark",
    *,
    iterations: int | tuple[int, int] | tuple[int, int, int] = (0, 3),
    compare: str | Mapping[str, Any] | None = None,
    window_size: tuple[int, int] | None = None,
    color_by: Any = None,
    edges: bool | None = None,
    **ranges: Any,
) -> Explorer:
    """Explore a scheme's parameters with sliders (re-run and re-render live).

    Parameters
    ----------
    mesh : Mesh or dict of str to Mesh
        The input; a dict adds a dropdown to choose it.
    scheme : str or sequence of str, default "catmull_clark"
        A scheme method of :class:`Mesh` (``catmull_clark``, ``doo_sabin``,
        ``loop``, ``sqrt3``, ``simplest``, ``midpoint``, ``dual``,
        ``honeycomb``, ``vertex_truncation``, ``sierpinski``, ``menger``);
        the dropdown offers every scheme, or only the ones in a sequence.
    iterations : int or (lo, hi) or (lo, hi, step), default (0, 3)
        The iterations slider's range (initial value 1), or its initial value.
    compare : str or dict, optional
        A second panel side by side, cameras linked: another scheme's name,
        or a dict of parameter values (may include ``"scheme"`` and
        ``"iterations"``) for the same scheme with other settings.
    window_size : (int, int), optional
        Of the whole image; default 480 × 400 per panel.
    color_by, edges
        As in :meth:`Mesh.plot` (``edges=None``: only below 20k faces).
    **ranges
        Per parameter (``t``, ``tension``, ``mode``, ``ratio``,
        ``thickness``, ``collapse_angle``): ``(lo, hi)`` or
        ``(lo, hi, step)`` for a slider (ints for an integer slider), a list
        for a dropdown, or a single value to fix it.

    Returns
    -------
    Explorer
        ``.widgets`` (set a ``.value`` to update), ``.mesh``, ``.image``,
        ``.png``, ``.timings``; displays itself in a notebook. Without
        ipywidgets the input and the results are shown as one static image.

    Raises
    ------
    MeshError
        Naming the scheme, parameter or range that is not allowed.
    """
    return Explorer(mesh, scheme, ranges, iterations, compare, window_size, color_by, edges)
