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


def _warn(message: str) -> None:
    import warnings

    warnings.warn(message, GeometryWarning, stacklevel=4)


def _per_vertex(mesh: Mesh, a: Any) -> Any:
    """Per-corner values ``a`` as per-vertex values, or None where two
    corners of one vertex differ (a seam)."""
    idx = np.asarray(mesh.face_indices, dtype=np.int64)
    out = np.zeros((mesh.n_vertices,) + a.shape[1:])
    out[idx] = a
    return out if np.array_equal(out[idx], a) else None


def _added_points(mesh: Mesh, values: Any, tris: Any, tri_face: Any) -> Any:
    """``values`` (V, ...) per vertex extended to the points ``triangulate()``
    adds: each added point gets the mean, over the faces whose triangles use
    it, of the mean of the face's vertex values."""
    n = mesh.n_vertices
    extra = int(tris.max()) + 1 - n if tris.size else 0
    if extra <= 0:
        return values
    sizes = np.asarray(mesh.face_sizes, dtype=np.int64)
    rows = values.reshape(n, -1)
    face_mean = np.add.reduceat(rows[mesh.face_indices], np.cumsum(sizes) - sizes, axis=0) / sizes[:, None]
    hit = tris >= n
    pairs = np.unique(np.stack([tris[hit] - n, np.repeat(tri_face, 3).reshape(-1, 3)[hit]], axis=1), axis=0)
    acc = np.zeros((extra, rows.shape[1]))
    np.add.at(acc, pairs[:, 0], face_mean[pairs[:, 1]])
    acc /= np.maximum(np.bincount(pairs[:, 0], minlength=extra), 1)[:, None]
    return np.concatenate([rows, acc]).reshape((n + extra,) + values.shape[1:])


def _colours(a: Any) -> Any:
    """uint8 RGB(A) of a (V, 3|4) attribute that looks like colours: values
    in [0, 1] (scaled by 255) or whole numbers in [0, 255]; else None."""
    if a.ndim != 2 or a.shape[1] not in (3, 4) or a.size == 0:
        return None
    if a.min() >= 0 and a.max() <= 1:
        return np.round(a * 255).astype(np.uint8)
    if a.min() >= 0 and a.max() <= 255 and np.array_equal(a, np.round(a)):
        return a.astype(np.uint8)
    return None


def to_trimesh(mesh: Mesh) -> Any:
    """``trimesh.Trimesh`` of ``mesh.triangulate()``: topomesh's vertices
    followed by the points the triangulation adds (``process=False``:
    nothing merged or removed). An open mesh stays open: hole faces are not
    triangulated, so trimesh sees the same boundary edges (``is_watertight``
    False). Emits :class:`GeometryWarning` if the mesh
    has cells with no geometric realization (see :func:`unrealized_cells`).

    Attributes: vertex attributes go to ``vertex_attributes`` (an added
    point gets the mean over the faces using it of their vertices' mean);
    face attributes to ``face_attributes``, each polygon's entry repeated on
    its triangles. A corner attribute ``"uv"`` becomes ``visual.uv``
    (trimesh's UVs are per vertex) when every vertex has one UV over all its
    corners; with seams it is left out with a :class:`GeometryWarning` (the
    vertices are not split, so the triangles keep topomesh's numbering), as
    are other corner attributes. Otherwise a vertex attribute ``"color"``
    (or ``"colour"``) of 3 or 4 columns that looks like colours (all values
    in [0, 1], scaled by 255, or whole numbers in [0, 255]) becomes
    ``visual.vertex_colors``. Creases have no trimesh counterpart."""
    trimesh = _need("trimesh")
    _warn_unrealized(mesh)
    verts, tris, tri_face = mesh.triangulate()
    vattr = {k: _added_points(mesh, np.asarray(a), tris, tri_face) for k, a in mesh.vertex_attributes.items()}
    fattr = {k: np.asarray(a)[tri_face] for k, a in mesh.face_attributes.items()}
    tm = trimesh.Trimesh(
        vertices=verts, faces=tris, process=False, vertex_attributes=vattr, face_attributes=fattr
    )
    corner = dict(mesh.corner_attributes)
    uv = corner.pop("uv", None)
    left = [f"corner attribute {k!r}" for k in corner]
    per_vertex = _per_vertex(mesh, uv) if uv is not None else None
    if uv is not None and per_vertex is None:
        left.insert(0, "corner attribute 'uv' (it has seams; trimesh stores one UV per vertex)")
    if per_vertex is not None:
        tm.visual = trimesh.visual.TextureVisuals(uv=_added_points(mesh, per_vertex, tris, tri_face))
    else:
        colour = next((vattr[k] for k in ("color", "colour") if k in vattr), None)
        rgba = _colours(colour) if colour is not None else None
        if rgba is not None:
            tm.visual = trimesh.visual.ColorVisuals(mesh=tm, vertex_colors=rgba)
    if left:
        _warn(f"to_trimesh: left out {', '.join(left)}")
    return tm


def to_pyvista(mesh: Mesh) -> Any:
    """``pyvista.PolyData`` with the polygon faces as they are (self-loop
    repeats and all; hole faces left out, so an open mesh stays open);
    pyvista triangulates on its own when it renders.

    Attributes: vertex attributes become ``point_data[name]``, face
    attributes ``cell_data[name]`` (one cell per polygon face, in face order;
    entries of more than one axis flattened to one row per face). VTK has no
    per-corner data on PolyData: a corner attribute ``"uv"`` becomes the
    active texture coordinates (point data ``"uv"``, unless a vertex
    attribute has that name: then ``"Texture Coordinates"``) when every
    vertex has one UV over all its corners; with seams, and for other
    corner attributes, it is left out with a :class:`GeometryWarning`."""
    pv = _need("pyvista")
    # a copy: VTK writes through NumPy views and ignores their read-only flag
    poly = pv.PolyData(np.array(mesh.vertices), mesh.padded_faces)
    for k, a in mesh.vertex_attributes.items():
        poly.point_data[k] = np.array(a)
    for k, a in mesh.face_attributes.items():
        a = np.array(a)
        poly.cell_data[k] = a.reshape(len(a), -1) if a.ndim > 2 else a
    corner = dict(mesh.corner_attributes)
    uv = corner.pop("uv", None)
    left = [f"corner attribute {k!r}" for k in corner]
    if uv is not None:
        per_vertex = _per_vertex(mesh, uv)
        if per_vertex is None:
            left.insert(0, "corner attribute 'uv' (it has seams; VTK stores one texture coordinate per point)")
        else:
            name = "uv" if "uv" not in mesh.vertex_attributes else "Texture Coordinates"
            poly.point_data[name] = per_vertex
            poly.point_data.active_texture_coordinates_name = name
    if left:
        _warn(f"to_pyvista: left out {', '.join(left)}")
    return poly


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
    vertex: dict | None = None,
    face: dict | None = None,
    corner: dict | None = None,
    source: str = "",
) -> Mesh:
    """``Mesh.from_flat`` (or the repair path) on the points the faces use:
    points no face refers to (pyvista keeps them after clipping, trimesh
    after ``process=False`` edits) are left out, the rest keep their order.
    ``vertex`` (per point), ``face`` (per face) and ``corner`` (per corner)
    attributes follow them; those that are not numbers (vertex, corner),
    have the wrong length or are not finite are left out with a
    :class:`GeometryWarning`; ``repair=True`` leaves all out (it renumbers
    vertices and faces and keeps no map)."""
    points = np.asarray(points, dtype=np.float64)
    indices = np.asarray(indices, dtype=np.int64).ravel()
    sizes = np.asarray(sizes, dtype=np.int64).ravel()
    keep = None
    if indices.size and indices.min() >= 0 and indices.max() < len(points):
        used = np.zeros(len(points), dtype=bool)
        used[indices] = True
        if not used.all():
            new = np.cumsum(used) - 1
            keep = used
            points, indices = points[used], new[indices]
    if repair:
        from topomesh._repair import repair_flat

        kw = dict(tolerance=tolerance, close_boundaries=close_boundaries, boundaries=boundaries)
        return repair_flat(points, sizes, indices, **kw)[0]
    attrs = _checked(source, len(used) if keep is not None else len(points), len(sizes), len(indices), vertex, face, corner)
    mesh = Mesh.from_flat(points, sizes, indices, close_boundaries=close_boundaries, boundaries=boundaries)
    v, f, c = attrs
    if keep is not None:
        v = {k: a[keep] for k, a in v.items()}
    if v or f or c:
        mesh = mesh.with_attributes(vertex=v or None, face=f or None, corner=c or None)
    return mesh


def _checked(source: str, n_points: int, n_faces: int, n_corners: int, vertex, face, corner) -> tuple:
    """The attributes :meth:`Mesh.with_attributes` takes, others warned about."""
    out: tuple = ({}, {}, {})
    bad = []
    for kind, d, n, o in (("vertex", vertex, n_points, out[0]), ("face", face, n_faces, out[1]), ("corner", corner, n_corners, out[2])):
        for k, a in (d or {}).items():
            a = np.asarray(a)
            numeric = a.dtype.kind in "iufb"
            if a.ndim == 0 or len(a) != n:
                bad.append(f"{kind} attribute {k!r} (length {len(a) if a.ndim else 'scalar'}, expected {n})")
            elif kind != "face" and not numeric:
                bad.append(f"{kind} attribute {k!r} (dtype {a.dtype}: numbers expected)")
            elif kind != "face" and not np.isfinite(a).all():
                bad.append(f"{kind} attribute {k!r} (not finite)")
            else:
                o[str(k)] = a.reshape(n, -1) if kind != "face" and a.ndim > 2 else a
    if bad:
        _warn(f"{source}: left out {'; '.join(bad)}")
    return out


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
    (or the legacy ``close_boundaries=False``) raises at a boundary edge.

    Attributes: the numeric arrays of ``tm.vertex_attributes`` become vertex
    attributes, ``tm.face_attributes`` face attributes (one per triangle),
    ``visual.uv`` (texture visuals) the corner attribute ``"uv"``, and
    ``visual.vertex_colors`` (when set and no vertex attribute is named
    ``"color"``) a vertex attribute ``"color"`` of RGBA in [0, 1]. Arrays of
    the wrong length, non-numeric or non-finite vertex data are left out
    with a :class:`GeometryWarning`; ``repair=True`` leaves all attributes
    out (it renumbers vertices and faces)."""
    if not (hasattr(tm, "vertices") and hasattr(tm, "faces")):
        raise MeshError(f"from_trimesh: expected a trimesh.Trimesh (vertices and faces), got {type(tm).__name__}")
    faces = np.asarray(tm.faces, dtype=np.int64).reshape(-1, 3)
    vertex = dict(getattr(tm, "vertex_attributes", {}) or {})
    face = dict(getattr(tm, "face_attributes", {}) or {})
    corner = {}
    visual = getattr(tm, "visual", None)
    kind = getattr(visual, "kind", None)
    if kind == "texture" and getattr(visual, "uv", None) is not None:
        uv = np.asarray(visual.uv, dtype=np.float64)
        if len(uv) == len(tm.vertices):
            corner["uv"] = uv[faces.ravel()]
    elif kind == "vertex" and "color" not in vertex:
        vertex["color"] = np.asarray(visual.vertex_colors, dtype=np.float64) / 255.0
    return _build(
        tm.vertices, np.full(len(faces), 3), faces, close_boundaries, repair, tolerance, boundaries,
        vertex, face, corner, "from_trimesh",
    )


def _cells(cells: Any) -> tuple[Any, Any]:
    """(sizes, connectivity) of a ``vtkCellArray``."""
    pv = _need("pyvista")
    offsets = np.asarray(pv.convert_array(cells.GetOffsetsArray()), dtype=np.int64)
    conn = np.asarray(pv.convert_array(cells.GetConnectivityArray()), dtype=np.int64)
    if offsets.size == 0:
        offsets = np.zeros(1, dtype=np.int64)
    return np.diff(offsets), conn


def _strip_triangles(sizes: Any, conn: Any) -> tuple[Any, Any]:
    """Triangles (T, 3) of triangle strips and the strip of each: triangle j
    of a strip is ``s[j], s[j+1], s[j+2]`` with the first two swapped for
    odd j (VTK's alternating orientation); triangles repeating a vertex (the
    stitches of degenerate strips) are left out."""
    n = np.maximum(sizes - 2, 0)
    if n.sum() == 0:
        return np.zeros((0, 3), dtype=np.int64), np.zeros(0, dtype=np.int64)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    first = np.repeat(starts, n)
    j = np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    a, b, c = conn[first + j], conn[first + j + 1], conn[first + j + 2]
    odd = j % 2 == 1
    a, b = np.where(odd, b, a), np.where(odd, a, b)
    t = np.stack([a, b, c], axis=1)
    keep = (a != b) & (b != c) & (a != c)
    return t[keep], np.repeat(np.arange(len(sizes)), n)[keep]


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
    Boundaries as in :func:`from_trimesh`: open surfaces stay open.

    Attributes: numeric ``point_data`` arrays become vertex attributes
    (arrays of more than two axes flattened per point), except the active
    texture coordinates, which become the corner attribute ``"uv"`` (the
    point's value at each of its corners); ``cell_data`` arrays become face
    attributes, the entries of the polygon cells one to one and each triangle
    strip's entry repeated on the triangles it is split into (vertex and
    line cells, which give no face, are skipped). Arrays that do not fit are
    left out with a :class:`GeometryWarning`; ``repair=True`` leaves all
    attributes out (it renumbers vertices and faces)."""
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
    tri, strip = _strip_triangles(*_cells(poly.GetStrips()))
    if len(tri):
        sizes = np.concatenate([sizes, np.full(len(tri), 3, dtype=np.int64)])
        conn = np.concatenate([conn, tri.ravel()])
    # PolyData numbers its cells verts, lines, polys, strips
    first = poly.GetNumberOfVerts() + poly.GetNumberOfLines()
    cells = np.concatenate([first + np.arange(poly.GetNumberOfPolys()), first + poly.GetNumberOfPolys() + strip])
    tcoords = poly.GetPointData().GetTCoords()
    tname = tcoords.GetName() if tcoords is not None else None
    vertex, corner = {}, {}
    for k in poly.point_data.keys():
        a = np.asarray(poly.point_data[k])
        if k == tname:
            corner["uv"] = np.asarray(a, dtype=np.float64)[conn] if a.dtype.kind in "iufb" else a
        else:
            vertex[k] = a
    face = {}
    for k in poly.cell_data.keys():
        a = np.asarray(poly.cell_data[k])
        face[k] = a[cells] if a.ndim and len(a) == poly.n_cells else a
    return _build(
        poly.points, sizes, conn, close_boundaries, repair, tolerance, boundaries, vertex, face, corner, "from_pyvista"
    )
