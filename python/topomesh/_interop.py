"""Conversions to the libraries users check and render with. Each import is
local so that none of them is needed unless its conversion is used."""

from __future__ import annotations

from typing import Any

import numpy as np

from topomesh._core import Mesh, MeshError


def _need(module: str, extra: str = "interop") -> Any:
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as e:
        raise ImportError(f"{module} is needed for this conversion: pip install 'topomesh[{extra}]'") from e


def to_trimesh(mesh: Mesh) -> Any:
    """``trimesh.Trimesh`` of ``mesh.triangles()`` with topomesh's vertex
    numbering (``process=False``: nothing merged or removed)."""
    trimesh = _need("trimesh")
    return trimesh.Trimesh(vertices=mesh.vertices, faces=mesh.triangles(), process=False)


def to_pyvista(mesh: Mesh) -> Any:
    """``pyvista.PolyData`` with the polygon faces as they are (self-loop
    repeats and all); pyvista triangulates on its own when it renders."""
    pv = _need("pyvista")
    # a copy: VTK writes through NumPy views and ignores their read-only flag
    return pv.PolyData(np.array(mesh.vertices), mesh.padded_faces)


def to_manifold(mesh: Mesh) -> Any:
    """``manifold3d.Manifold`` of ``mesh.triangles()`` (float32 positions, as
    manifold3d stores them). Raises :class:`MeshError` if manifold3d rejects
    the triangles (its status is in the message)."""
    m3d = _need("manifold3d")
    tris = mesh.triangles()
    m = m3d.Manifold(
        m3d.Mesh(vert_properties=np.asarray(mesh.vertices, dtype=np.float32), tri_verts=np.asarray(tris, dtype=np.uint32))
    )
    status = m.status()
    if status != m3d.Error.NoError:
        raise MeshError(f"manifold3d rejected the triangulated mesh: {status}")
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
