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
    nothing merged or removed). Emits :class:`GeometryWarning` if the mesh
    has cells with no geometric realization (see :func:`unrealized_cells`)."""
    trimesh = _need("trimesh")
    _warn_unrealized(mesh)
    verts, tris, _ = mesh.triangulate()
    return trimesh.Trimesh(vertices=verts, faces=tris, process=False)


def to_pyvista(mesh: Mesh) -> Any:
    """``pyvista.PolyData`` with the polygon faces as they are (self-loop
    repeats and all); pyvista triangulates on its own when it renders."""
    pv = _need("pyvista")
    return pv.PolyData(mesh.vertices, mesh.padded_faces)


def to_manifold(mesh: Mesh) -> Any:
    """``manifold3d.Manifold`` of ``mesh.triangulate()`` (float32 positions, as
    manifold3d stores them). Emits :class:`GeometryWarning` if the mesh has
    cells with no geometric realization; raises :class:`MeshError` if
    manifold3d rejects the triangles (its status is in the message) or its
    genus differs from ``mesh.genus - (mesh.n_components - 1)``."""
    m3d = _need("manifold3d")
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


def from_trimesh(tm: Any, close_boundaries: bool = False) -> Mesh:
    """A :class:`Mesh` from a ``trimesh.Trimesh`` (its vertices and triangles as they are)."""
    return Mesh.from_polygons(np.asarray(tm.vertices), np.asarray(tm.faces), close_boundaries=close_boundaries)


def from_pyvista(poly: Any, close_boundaries: bool = False) -> Mesh:
    """A :class:`Mesh` from a ``pyvista.PolyData`` with polygon faces."""
    pv = _need("pyvista")
    cells = poly.GetPolys()
    offsets = np.asarray(pv.convert_array(cells.GetOffsetsArray()), dtype=np.int64)
    conn = np.asarray(pv.convert_array(cells.GetConnectivityArray()), dtype=np.int64)
    return Mesh.from_flat(np.asarray(poly.points), np.diff(offsets), conn, close_boundaries=close_boundaries)
