"""Conversions to the libraries users check and render with. Each import is
local so that none of them is needed unless its conversion is used."""

from __future__ import annotations

from typing import Any

import numpy as np

from topomesh._core import GeometryWarning, Mesh, MeshError


def _need(module: str, extra: str = "interop") -> Any:
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as e:
        raise ImportError(f"{module} is needed for this conversion: pip install 'topomesh[{extra}]'") from e


def unrealized_cells(mesh: Mesh) -> dict[str, int]:
    """Cells with no geometric realization as triangles, by kind: self-loops,
    one-gons and point-spheres (``"one-gons"``), two-gons, and faces with a
    vertex repeated apart from self-loops. ``triangulate()`` drops the loops
    and the faces left with fewer than three corners; the triangle mesh
    pinches there."""
    sizes = np.asarray(mesh.face_sizes, dtype=np.int64)
    idx = np.asarray(mesh.face_indices, dtype=np.int64)
    out = {"self-loops": int(mesh.n_self_loops), "one-gons": 0, "two-gons": 0, "faces with a repeated vertex": 0}
    if len(sizes) == 0:
        return out
    start = np.repeat(np.cumsum(sizes) - sizes, sizes)
    pos = np.arange(len(idx)) - start
    nxt = start + (pos + 1) % np.repeat(sizes, sizes)
    # corners left after dropping consecutive repeats (self-loops)
    keep = idx != idx[nxt]
    face = np.repeat(np.arange(len(sizes)), sizes)
    kept = np.bincount(face[keep], minlength=len(sizes))
    out["one-gons"] = int(np.count_nonzero(kept <= 1))
    out["two-gons"] = int(np.count_nonzero(kept == 2))
    nv = max(mesh.n_vertices, 1)
    distinct = np.bincount(np.unique(face[keep] * nv + idx[keep]) // nv, minlength=len(sizes))
    out["faces with a repeated vertex"] = int(np.count_nonzero((kept >= 3) & (distinct < kept)))
    return out


def _warn_unrealized(mesh: Mesh) -> None:
    cells = {k: v for k, v in unrealized_cells(mesh).items() if v}
    if cells:
        import warnings

        what = " and ".join(f"{v} {k}" for k, v in cells.items())
        warnings.warn(
            f"{what} have no geometric realization; the triangle mesh pinches there", GeometryWarning, stacklevel=3
        )


def to_trimesh(mesh: Mesh) -> Any:
    """``trimesh.Trimesh`` of ``mesh.triangulate()``: topomesh's vertices
    followed by the points the triangulation adds (``process=False``:
    nothing merged or removed). An open mesh stays open: hole faces are not
    triangulated, so trimesh sees the same boundary edges (``is_watertight``
    False). Emits :class:`GeometryWarning` if the mesh
    has cells with no geometric realization (see :func:`unrealized_cells`)."""
    trimesh = _need("trimesh")
    _warn_unrealized(mesh)
    verts, tris, _ = mesh.triangulate()
    return trimesh.Trimesh(vertices=verts, faces=tris, process=False)


def to_pyvista(mesh: Mesh) -> Any:
    """``pyvista.PolyData`` with the polygon faces as they are (self-loop
    repeats and all; hole faces left out, so an open mesh stays open);
    pyvista triangulates on its own when it renders."""
    pv = _need("pyvista")
    # a copy: VTK writes through NumPy views and ignores their read-only flag
    return pv.PolyData(np.array(mesh.vertices), mesh.padded_faces)


def to_manifold(mesh: Mesh) -> Any:
    """``manifold3d.Manifold`` of ``mesh.triangulate()`` (float32 positions, as
    manifold3d stores them). Emits :class:`GeometryWarning` if the mesh has
    cells with no geometric realization; raises :class:`MeshError` for an
    open mesh (manifold3d holds closed solids), if manifold3d rejects the triangles (its status is in the message) or its
    genus differs from ``mesh.genus - (mesh.n_components - 1)``."""
    m3d = _need("manifold3d")
    if not mesh.is_closed:
        a, b = (int(x) for x in mesh.boundary_edges()[0])
        raise MeshError(
            f"to_manifold: the mesh is open ({mesh.n_boundary_loops} boundary loop"
            f"{'s' if mesh.n_boundary_loops != 1 else ''}, e.g. boundary edge ({a}, {b})); "
            "manifold3d holds closed solids only"
        )
    _warn_unrealized(mesh)
    verts, tris, _ = mesh.triangulate()
    m = m3d.Manifold(
        m3d.Mesh(vert_properties=np.asarray(verts, dtype=np.float32), tri_verts=np.asarray(tris, dtype=np.uint32))
    )
    status = m.status()
    if status != m3d.Error.NoError:
        raise MeshError(f"manifold3d rejected the triangulated mesh: {status}")
    want = mesh.genus - (mesh.n_components - 1)
    if m.genus() != want:
        raise MeshError(
            f"manifold3d sees genus {m.genus()} where topomesh has {want} "
            f"(genus {mesh.genus} over {mesh.n_components} components): the triangle mesh pinches"
        )
    return m


def _build(
    points: Any,
    sizes: Any,
    indices: Any,
    close_boundaries: bool | None,
    repair: bool,
    tolerance: float | None,
    boundaries: str = "keep",
) -> Mesh:
    """``Mesh.from_flat`` (or the repair path) on the points the faces use:
    points no face refers to (pyvista keeps them after clipping, trimesh
    after ``process=False`` edits) are left out, the rest keep their order."""
    points = np.asarray(points, dtype=np.float64)
    indices = np.asarray(indices, dtype=np.int64).ravel()
    sizes = np.asarray(sizes, dtype=np.int64).ravel()
    if indices.size and indices.min() >= 0 and indices.max() < len(points):
        used = np.zeros(len(points), dtype=bool)
        used[indices] = True
        if not used.all():
            new = np.cumsum(used) - 1
            points, indices = points[used], new[indices]
    if repair:
        from topomesh._repair import repair_flat

        kw = dict(tolerance=tolerance, close_boundaries=close_boundaries, boundaries=boundaries)
        return repair_flat(points, sizes, indices, **kw)[0]
    return Mesh.from_flat(points, sizes, indices, close_boundaries=close_boundaries, boundaries=boundaries)


def from_trimesh(
    tm: Any,
    close_boundaries: bool | None = None,
    repair: bool = False,
    tolerance: float | None = None,
    boundaries: str = "keep",
) -> Mesh:
    """A :class:`Mesh` from a ``trimesh.Trimesh``: its vertices and triangles
    (vertices no triangle uses left out). ``repair=True`` passes them through
    :func:`topomesh.repair` with ``tolerance`` (call it directly for the report).
    An open mesh stays open (``boundaries="keep"``); ``boundaries="refuse"``
    (or the legacy ``close_boundaries=False``) raises at a boundary edge."""
    faces = np.asarray(tm.faces, dtype=np.int64).reshape(-1, 3)
    return _build(tm.vertices, np.full(len(faces), 3), faces, close_boundaries, repair, tolerance, boundaries)


def _cells(cells: Any) -> tuple[Any, Any]:
    """(sizes, connectivity) of a ``vtkCellArray``."""
    pv = _need("pyvista")
    offsets = np.asarray(pv.convert_array(cells.GetOffsetsArray()), dtype=np.int64)
    conn = np.asarray(pv.convert_array(cells.GetConnectivityArray()), dtype=np.int64)
    if offsets.size == 0:
        offsets = np.zeros(1, dtype=np.int64)
    return np.diff(offsets), conn


def _strip_triangles(sizes: Any, conn: Any) -> Any:
    """Triangles (T, 3) of triangle strips: triangle j of a strip is
    ``s[j], s[j+1], s[j+2]`` with the first two swapped for odd j (VTK's
    alternating orientation); triangles repeating a vertex (the stitches of
    degenerate strips) are left out."""
    n = np.maximum(sizes - 2, 0)
    if n.sum() == 0:
        return np.zeros((0, 3), dtype=np.int64)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    first = np.repeat(starts, n)
    j = np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    a, b, c = conn[first + j], conn[first + j + 1], conn[first + j + 2]
    odd = j % 2 == 1
    a, b = np.where(odd, b, a), np.where(odd, a, b)
    t = np.stack([a, b, c], axis=1)
    keep = (a != b) & (b != c) & (a != c)
    return t[keep]


def from_pyvista(
    data: Any,
    close_boundaries: bool | None = None,
    repair: bool = False,
    tolerance: float | None = None,
    boundaries: str = "keep",
) -> Mesh:
    """A :class:`Mesh` from a pyvista dataset.

    ``PolyData``: its polygon faces, then its triangle strips as triangles
    (vertex and line cells are not surface cells and are left out). Any
    other dataset (``UnstructuredGrid``, ``ImageData``, ...) goes through
    ``extract_surface()`` first. Points no face uses are left out.
    ``repair=True`` passes the faces through :func:`topomesh.repair`.
    Boundaries as in :func:`from_trimesh`: open surfaces stay open."""
    pv = _need("pyvista")
    poly = data
    if not isinstance(poly, pv.PolyData):
        if not hasattr(poly, "extract_surface"):
            raise MeshError(f"from_pyvista: expected a pyvista dataset, got {type(data).__name__}")
        try:  # pyvista >= 0.45 warns unless the algorithm is named
            poly = poly.extract_surface(algorithm="dataset_surface")
        except TypeError:
            poly = poly.extract_surface()
    sizes, conn = _cells(poly.GetPolys())
    tri = _strip_triangles(*_cells(poly.GetStrips()))
    if len(tri):
        sizes = np.concatenate([sizes, np.full(len(tri), 3, dtype=np.int64)])
        conn = np.concatenate([conn, tri.ravel()])
    return _build(poly.points, sizes, conn, close_boundaries, repair, tolerance, boundaries)
