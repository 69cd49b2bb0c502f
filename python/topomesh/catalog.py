"""The catalog: every scheme, remeshing and Conway operator of topomesh in one list.

``topomesh.catalog()`` is what a notebook user browses to find a rule by its
name, its source or its counts; each entry names the :class:`~topomesh.Mesh`
method that runs it. The TopMod entries are the machine-readable list of
``docs/schemes/topmod.md`` (a test keeps the two equal), the Conway entries
come from :func:`topomesh.conway_operators`.
"""

from __future__ import annotations

from typing import Any

# (name, method, source, V', E', F') of the schemes that were there before the
# remeshing catalog: the papers' schemes and the classic smoothing ones
_SCHEMES = [
    ("Catmull-Clark", "catmull_clark", "Catmull & Clark 1978; OpenSubdiv rules", "V+E+F", "2E+H", "H"),
    ("Loop", "loop", "Loop 1987; OpenSubdiv rules", "V+E", "2E+3F", "4F"),
    ("Doo-Sabin", "doo_sabin", "Doo & Sabin 1978", "H", "2E+H", "V+E+F"),
    ("sqrt3", "sqrt3", "Kobbelt 2000", "V+F", "3E", "2E"),
    ("simplest", "simplest", "Peters & Reif 1997", "E", "2E", "F+V"),
    ("midpoint", "midpoint", "linear: 1-to-4 triangles, a face point in other faces", "V+E+F", "2E+H", "H"),
    ("dual", "dual", "Poincaré dual", "F", "E", "V"),
    ("honeycomb", "honeycomb", "Akleman & Srinivasan, Honeycomb Subdivision", "2E", "3E", "F+V"),
    ("vertex truncation", "vertex_truncation", "Akleman, Edmundson & Ozener, Generalized Vertex Truncation", "H", "E+H", "F+V"),
    ("Sierpinski", "sierpinski", "Srinivasan & Akleman, Connected & Manifold Sierpinsky Polyhedra", "see docs", "see docs", "see docs"),
    ("generalized Menger sponge", "menger", "Srinivasan, Modeling High-Genus Surfaces, ch. VII", "see docs", "see docs", "see docs"),
]

# TopMod's remeshing menu (docs/schemes/topmod.md, its machine-readable list)
_TOPMOD: list[dict[str, Any]] = [
    {"name": "stellate", "method": "stellate", "params": {"offset": 0.0}, "source": "DLFLSubdiv.cc subdivideAllFaces(false)", "V": "V+F", "E": "3E", "F": "2E"},
    {"name": "double stellate", "method": "double_stellate", "params": {"offset": 0.0}, "source": "DLFLSubdiv.cc starSubdivide", "V": "V+F+2E", "E": "9E", "F": "6E"},
    {"name": "stellate with edge removal", "method": "stellate_edge_removal", "params": {}, "source": "DLFLSubdiv.cc stellateSubdivide", "V": "V+F", "E": "2E", "F": "E"},
    {"name": "double stellate (misc.)", "method": "double_stellate_misc", "params": {"height": 0.0, "curve": 0.0}, "source": "DLFLSubdiv.cc twostellateSubdivide", "V": "V+F+2E", "E": "6E", "F": "3E"},
    {"name": "linear vertex insertion", "method": "linear_vertex_insertion", "params": {}, "source": "DLFLSubdiv.cc subdivideAllFaces(true)", "V": "V+E+F", "E": "4E", "F": "2E"},
    {"name": "corner cutting", "method": "corner_cutting", "params": {"alpha": 0.5625}, "source": "DLFLSubdiv.cc cornerCuttingSubdivide", "V": "2E", "E": "4E", "F": "F+E+V"},
    {"name": "modified corner cutting", "method": "modified_corner_cutting", "params": {"thickness": 0.25}, "source": "DLFLSubdiv.cc modifiedCornerCuttingSubdivide", "V": "2E", "E": "4E", "F": "F+E+V"},
    {"name": "root-3", "method": "root3", "params": {}, "source": "MainWindowCallbacks.cc subdivideRoot3", "V": "V+F", "E": "3E", "F": "2E"},
    {"name": "Loop-style", "method": "loop_style", "params": {"length": 1.0}, "source": "DLFLSubdiv.cc loopStyleSubdivide", "V": "V+E", "E": "4E", "F": "F+2E"},
    {"name": "root-4", "method": "root4", "params": {"weight": 0.0, "twist": 0.0}, "source": "DLFLSubdiv.cc root4Subdivide", "V": "V+2E", "E": "4E", "F": "F+E"},
    {"name": "dual Loop-style", "method": "dual_loop_style", "params": {"weight": 0.0, "twist": 0.0}, "source": "RemeshingMode.cc (runs root4Subdivide)", "V": "V+2E", "E": "4E", "F": "F+E"},
    {"name": "hexagon preserving", "method": "hexagon_preserving", "params": {"weight": 0.0, "twist": 0.0}, "source": "MainWindow.cc HexagonPreserving (runs root4Subdivide)", "V": "V+2E", "E": "4E", "F": "F+E"},
    {"name": "dual hexagon preserving", "method": "dual_hexagon_preserving", "params": {"weight": 0.0, "twist": 0.0}, "source": "MainWindowCallbacks.cc subdivideDualHexagonPreserving", "V": "V+E", "E": "4E", "F": "F+2E"},
    {"name": "dual Loop", "method": "dual_loop", "params": {}, "source": "MainWindowCallbacks.cc subdivideDualLoop", "V": "4F_t", "E": "2E_t+3F_t", "F": "V_t+E_t"},
    {"name": "pentagonalization", "method": "pentagonalize", "params": {"offset": 0.0}, "source": "DLFLSubdiv.cc pentagonalSubdivide", "V": "V+2E+F", "E": "5E", "F": "2E"},
    {"name": "cubic pentagonalization", "method": "cubic_pentagonalize", "params": {"offset": 0.0}, "source": "MainWindowCallbacks.cc subdivideCubicPentagonal", "V": "V+2E+F", "E": "5E", "F": "2E"},
    {"name": "dual pentagonalization", "method": "dual_pentagonalize", "params": {"offset": 0.0}, "source": "MainWindowCallbacks.cc subdivideDualPentagonal", "V": "2E", "E": "5E", "F": "V+F+2E"},
    {"name": "pentagon preserving", "method": "pentagon_preserving", "params": {"scale": 0.75}, "source": "DLFLSubdiv.cc pentagonalSubdivide2", "V": "V+E+H3", "E": "2E+2H3", "F": "F+H3"},
    {"name": "dual pentagon preserving", "method": "dual_pentagon_preserving", "params": {"scale": 0.75}, "source": "MainWindowCallbacks.cc subdivideDualPentagonPreserving", "V": "V+S", "E": "2E+2S", "F": "F+E+S"},
    {"name": "dual 12.6.4", "method": "dual_12_6_4", "params": {"scale": 0.7}, "source": "DLFLSubdiv.cc dual1264Subdivide", "V": "4E", "E": "6E", "F": "F+E+V"},
    {"name": "12.6.4", "method": "remesh_12_6_4", "params": {"scale": 0.7}, "source": "MainWindowCallbacks.cc subdivide1264", "V": "V+E+F", "E": "6E", "F": "4E"},
    {"name": "checkerboard", "method": "checkerboard", "params": {"thickness": 0.33}, "source": "DLFLSubdiv.cc checkerBoardRemeshing", "V": "V+4E", "E": "9E", "F": "F+4E"},
    {"name": "dual checkerboard", "method": "dual_checkerboard", "params": {"thickness": 0.33}, "source": "MainWindowCallbacks.cc subdivideDualCheckerBoard", "V": "V+4E", "E": "9E", "F": "F+4E"},
    {"name": "Doo-Sabin BC", "method": "doo_sabin_bc", "params": {}, "source": "DLFLSubdiv.cc dooSabinSubdivideBC", "V": "4E", "E": "8E", "F": "F+3E+V"},
    {"name": "Doo-Sabin BC new", "method": "doo_sabin_bc_new", "params": {"scale": 1.0, "length": 1.0}, "source": "DLFLSubdiv.cc dooSabinSubdivideBCNew", "V": "V+4E", "E": "7E", "F": "F+2E"},
    {"name": "dome", "method": "dome", "params": {"length": 1.0, "scale": 1.0}, "source": "DLFLSubdiv.cc domeSubdivide", "V": "V+59E", "E": "116E", "F": "F+56E"},
    {"name": "fractal", "method": "fractal", "params": {"offset": 1.0}, "source": "DLFLSubdiv.cc fractalSubdivide", "V": "V+E+F", "E": "6E", "F": "4E"},
    {"name": "subdivide selected faces", "method": "subdivide_faces", "params": {"faces": [], "quads": True}, "source": "DLFLSubdiv.cc subdivideFaces", "V": "V+s+k", "E": "E+s+N", "F": "F-k+N"},
    {"name": "extrusion", "method": "extrude", "params": {"faces": [], "kind": "cubical", "length": None, "scale": 1.0, "twist": 0.0, "segments": 1, "angle": None, "lengths": None}, "source": "DLFLExtrude.cc", "V": "see table", "E": "see table", "F": "see table"},
]

# TopMod's high-genus tools (docs/tools.md): counts with their default parameters;
# V1, V2, V3 are the vertices of valence 1, 2 and >= 3
_TOOLS: list[dict[str, Any]] = [
    {"name": "wireframe", "method": "wireframe", "params": {"thickness": 0.1, "width": None}, "source": "DLFLCrust.cc makeWireframe, makeWireframe2", "V": "4E", "E": "10E", "F": "2V+4E"},
    {"name": "column modelling", "method": "wireframe_columns", "params": {"thickness": 0.25, "segments": 4}, "source": "DLFLCrust.cc makeWireframeWithColumns", "V": "8E", "E": "12E+3(2E-V1)-2V2", "F": "4E+2(2E-V1)+2V3+V1"},
    {"name": "multi-face handle (convex hull)", "method": "multi_face_handle", "params": {"faces": [], "scale": 1.0, "extrude": 0.5, "algorithm": "convex_hull"}, "source": "DLFLMultiConnect.cc multiConnectFaces(faces, sf, d, offsets)", "V": "see docs", "E": "see docs", "F": "see docs"},
    {"name": "multi-face handle (closest edge)", "method": "multi_face_handle", "params": {"faces": [], "algorithm": "closest_edge"}, "source": "DLFLMultiConnect.cc multiConnectFaces(faces)", "V": "V", "E": "see docs", "F": "see docs"},
]


def catalog(family: str | None = None) -> list[dict[str, Any]]:
    """Every scheme and operator of topomesh, as a list of dicts.

    Parameters
    ----------
    family : {"scheme", "topmod", "tool", "conway"}, optional
        Only that family: the papers' and classic smoothing schemes, TopMod's
        remeshing menu, TopMod's high-genus tools (wireframe, columns,
        multi-face handle), or Conway's operators.

    Returns
    -------
    list of dict
        Each with ``family``, ``name``, ``method`` (the :class:`Mesh` method
        that runs it), ``source`` (paper, TopMod function or Hart's
        notation) and the per-iteration counts ``V``, ``E``, ``F`` in terms of
        the input's (``H = 2E`` half-edges); TopMod and tool entries also give
        their default ``params``, Conway entries their ``letter``.

    Examples
    --------
    >>> import topomesh
    >>> [e["method"] for e in topomesh.catalog("scheme")][:3]
    ['catmull_clark', 'loop', 'doo_sabin']
    """
    from . import MeshError, conway_operators

    families = ("scheme", "topmod", "tool", "conway")
    if family is not None and family not in families:
        raise MeshError(f"catalog: family = {family!r}; expected one of {', '.join(map(repr, families))} or None")
    out: list[dict[str, Any]] = []
    if family in (None, "scheme"):
        for n, m, s, v, e, f in _SCHEMES:
            entry = {"family": "scheme", "name": n, "method": m, "source": s, "V": v, "E": e, "F": f}
            if m == "loop":
                entry["input"] = "triangles"  # other faces are fanned into triangles first
            elif m == "midpoint":
                entry["input"] = "no triangles"  # triangles get no face point: V' = V + E + (non-triangle faces)
            out.append(entry)
    if family in (None, "topmod"):
        out += [{"family": "topmod", **{k: (dict(v) if isinstance(v, dict) else v) for k, v in e.items()}} for e in _TOPMOD]
    if family in (None, "tool"):
        out += [{"family": "tool", **{k: (dict(v) if isinstance(v, dict) else v) for k, v in e.items()}} for e in _TOOLS]
    if family in (None, "conway"):
        for op in conway_operators():
            v, e, f = op["counts"]
            out.append({
                "family": "conway",
                "name": op["name"],
                "method": op["method"],
                "letter": op["letter"],
                "source": "Hart, Conway Notation for Polyhedra" + (f" ({op['definition']})" if op["definition"] else ""),
                "V": v, "E": e, "F": f,
            })
    return out


def schemes(family: str | None = None) -> list[dict[str, Any]]:
    """The catalog as a table: the same rows as :func:`catalog`, one per
    scheme, remeshing, tool and Conway operator (``family``, ``name``,
    ``method``, ``source``, default ``params`` where it has any, and the
    per-iteration counts ``V``, ``E``, ``F``).

    ``notebooks/06_catalog.ipynb`` runs every row on a cube and on a genus-2
    surface; ``topomesh.catalog.run_entry(row, mesh)`` runs one row on a mesh.

    Examples
    --------
    >>> import topomesh
    >>> len(topomesh.schemes()) == len(topomesh.catalog())
    True
    """
    return catalog(family)


def default_selection(entry: dict[str, Any], mesh: Any) -> list[int]:
    """The faces an entry with a ``faces`` parameter is shown on when none
    are given: the highest and the lowest face (by centroid ``z``) for the
    multi-face handles (two faces whose hub is the body between them), else
    the three faces nearest the corner in the direction (1, 0.9, 0.8)."""
    import numpy as np

    c = mesh.face_centroids
    if entry["method"] == "multi_face_handle":
        return [int(np.argmax(c[:, 2])), int(np.argmin(c[:, 2]))]
    return [int(i) for i in np.argsort(-(c @ np.array([1.0, 0.9, 0.8])))[:3]]


def run_entry(entry: dict[str, Any], mesh: Any, **params: Any) -> Any:
    """Run one catalog row on ``mesh`` with its default parameters (updated
    by ``params``) and return the output :class:`~topomesh.Mesh`.

    An empty ``faces`` selection is filled by :func:`default_selection`; the
    convex-hull multi-face handle then gets ``scale=0.5, extrude=-0.25`` (its
    hub inside the body; the defaults make a hub outside, which needs faces
    that look at one point). Tools that return ``(mesh, residual)`` give the
    mesh.
    """
    p = {k: (list(v) if isinstance(v, list) else v) for k, v in entry.get("params", {}).items()}
    if "faces" in p and not p["faces"] and "faces" not in params:
        p["faces"] = default_selection(entry, mesh)
        if entry["method"] == "multi_face_handle" and p.get("algorithm") == "convex_hull":
            p.update(scale=0.5, extrude=-0.25)
    p.update(params)
    out = getattr(mesh, entry["method"])(**p)
    return out[0] if isinstance(out, tuple) else out
