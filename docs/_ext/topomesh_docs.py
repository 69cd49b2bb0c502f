"""Sphinx extension of the topomesh site: signatures from the stubs, the
small gallery, and static notebook output.

* ``autodoc`` reads the compiled extension's docstrings (written once on the
  Rust ``#[pyfunction]``/``#[pymethods]``), whose ``__text_signature__`` has no
  types; :func:`stub_signature` replaces the signature of every object of
  ``topomesh._core`` by the one in ``python/topomesh/_core.pyi`` (overloads
  included), so the reference shows the checked stub types.
* :func:`make_gallery` renders the entries in :data:`GALLERY` with
  ``topomesh.gallery.run`` into ``docs/_build/gallery`` (not committed); the
  scheme pages and ``gallery.md`` show them.
* The notebook kernels get an IPython startup file that displays a
  ``topomesh.explore`` explorer as its current PNG: its sliders need a live
  kernel, which a rendered page does not have.
"""

from __future__ import annotations

import ast
import inspect
import os
import time
from pathlib import Path
from typing import Any

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
STUBS = ROOT / "python" / "topomesh" / "_core.pyi"
#: generated gallery (inside the source dir, so Sphinx copies the images; under _build, so never committed)
GALLERY_DIR = DOCS / "_build" / "gallery"
#: the gallery entries the site shows (names of topomesh.gallery entries and pictures)
GALLERY = [
    # the landing page
    "genus3", "tetrahedron_sierpinski_doo_sabin",
    # subdivision and smoothing
    "cube_catmull_clark", "cube_doo_sabin", "cube_loop", "cube_sqrt3", "cube_simplest", "cube_midpoint", "cube_dual",
    # high-genus remeshing
    "dodecahedron_honeycomb", "cube_truncation", "dodecahedron_truncation",
    "cup", "arch_cube_3", "twisted_handle", "peeled_rind_sphere",
    # fractals
    "tetrahedron_sierpinski", "cube_sierpinski_doo_sabin", "star_prism_sierpinski_doo_sabin",
    "menger_sponge_1", "menger_sponge_2", "cube_menger", "tetrahedron_menger", "dodecahedron_menger",
    "octahedron_menger", "tetrahedron_menger_merged",
    # attractors
    "ifs_cubic_bspline", "ifs_koch", "ifs_gasket",
]

_STARTUP = '''\
# Written by docs/_ext/topomesh_docs.py for the documentation build only.
def _topomesh_static_explorer(explorer):
    from IPython.display import Image, display
    display(Image(data=explorer.png, format="png"))


get_ipython().display_formatter.ipython_display_formatter.for_type_by_name(
    "topomesh.explore", "Explorer", _topomesh_static_explorer
)
'''


# ---------------------------------------------------------------- stubs


def _stub_signatures(path: Path = STUBS) -> dict[str, list[tuple[str, str]]]:
    """``{qualname: [(args, return annotation), ...]}`` of every function and
    method in the stub file (one entry per overload); ``self`` is dropped."""
    tree = ast.parse(path.read_text())
    out: dict[str, list[tuple[str, str]]] = {}

    def visit(body: list[ast.stmt], prefix: str) -> None:
        for node in body:
            if isinstance(node, ast.ClassDef):
                visit(node.body, f"{prefix}{node.name}.")
            elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                args = node.args
                decorators = {ast.unparse(d) for d in node.decorator_list}
                if prefix and "staticmethod" not in decorators and args.args and args.args[0].arg == "self":
                    args = ast.arguments(
                        posonlyargs=args.posonlyargs, args=args.args[1:], vararg=args.vararg, kwonlyargs=args.kwonlyargs,
                        kw_defaults=args.kw_defaults, kwarg=args.kwarg, defaults=args.defaults,
                    )
                sig = f"({ast.unparse(args)})"
                ret = ast.unparse(node.returns) if node.returns is not None else ""
                entry = out.setdefault(prefix + node.name, [])
                if "overload" not in decorators and entry:
                    continue  # the implementation after its overloads
                entry.append((sig, ret))

    visit(tree.body, "")
    return out


def _core_qualname(obj: Any) -> str | None:
    """The qualified name of a compiled ``topomesh._core`` function, method
    or property (the stub's name for it), or None for Python code."""
    if not (inspect.isbuiltin(obj) or inspect.ismethoddescriptor(obj) or inspect.isgetsetdescriptor(obj)):
        return None
    return getattr(obj, "__qualname__", None)


_SIGS: dict[str, list[tuple[str, str]]] | None = None  # read once per build


def _stub(app: Any, obj: Any) -> list[tuple[str, str]] | None:
    global _SIGS
    if _SIGS is None:
        _SIGS = _stub_signatures()
    q = _core_qualname(obj)
    return _SIGS.get(q) if q is not None else None


def stub_signature(app: Any, what: str, name: str, obj: Any, options: Any, signature: str | None, return_annotation: str | None) -> Any:
    """The stub's signature (the first overload) instead of the untyped
    ``__text_signature__``."""
    if what not in ("function", "method"):
        return None
    found = _stub(app, obj)
    return found[0] if found else None


def stub_docstring(app: Any, what: str, name: str, obj: Any, options: Any, lines: list[str]) -> None:
    """Overloads after the first and the types of compiled properties, from
    the stubs (autodoc reads neither from an extension module)."""
    found = _stub(app, obj)
    if not found:
        return
    if what in ("function", "method") and len(found) > 1:
        short = name.rsplit(".", 1)[-1]
        lines += ["", "Overloads (from the stubs):", ""]
        lines += [f"* ``{short}{args} -> {ret}``" for args, ret in found]
    elif what in ("attribute", "property") and found[0][1]:
        lines += ["", f"Type (from the stubs): ``{found[0][1]}``"]


# -------------------------------------------------------------- gallery


def make_gallery(app: Any) -> None:
    """Render :data:`GALLERY` and write ``page.md`` (a grid of the renders
    and the peer table) for ``gallery.md`` to include."""
    from topomesh import gallery

    t0 = time.perf_counter()
    GALLERY_DIR.mkdir(parents=True, exist_ok=True)
    rows = gallery.run(GALLERY_DIR, only=GALLERY, progress=False)
    missing = [n for n in GALLERY if not (GALLERY_DIR / f"{n}.png").is_file()]
    if missing:
        raise RuntimeError(f"gallery entries not rendered: {', '.join(missing)}")
    titles = {e.name: e.title for e in gallery.entries()} | {p.name: p.title for p in gallery.pictures()}
    lines = []
    for n in GALLERY:
        lines += [f"```{{image}} /_build/gallery/{n}.png", f":alt: {titles[n]}", ":width: 32%", "```"]
    cols = {"V": "V", "E": "E", "F": "F", "genus": "genus", "self_loops": "loops",
            "trimesh_watertight": "trimesh closed", "trimesh_genus": "trimesh genus", "manifold_genus": "manifold3d genus"}
    lines += ["", "| entry | " + " | ".join(cols.values()) + " |", "|---" * (len(cols) + 1) + "|"]
    for r in rows:
        cells = [str(r.get(c, "")).replace(" (smoothed)", "*") for c in cols]
        lines.append(f"| {r['title']} | " + " | ".join(cells) + " |")
    lines += ["", "\\* after two Doo-Sabin steps, which open the zero-length self-loops."]
    (GALLERY_DIR / "page.md").write_text("\n".join(lines) + "\n")
    from sphinx.util import logging

    logging.getLogger(__name__).info(f"gallery: {len(GALLERY)} images in {time.perf_counter() - t0:.1f} s -> {GALLERY_DIR}")


# ------------------------------------------------------------- notebooks


def kernel_startup(app: Any) -> None:
    ipython_dir = DOCS / "_build" / "ipython"
    startup = ipython_dir / "profile_default" / "startup"
    startup.mkdir(parents=True, exist_ok=True)
    (startup / "00-topomesh-docs.py").write_text(_STARTUP)
    os.environ["IPYTHONDIR"] = str(ipython_dir)


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", make_gallery)
    app.connect("builder-inited", kernel_startup)
    app.connect("autodoc-process-signature", stub_signature)
    app.connect("autodoc-process-docstring", stub_docstring)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
