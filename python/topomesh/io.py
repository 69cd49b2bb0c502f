"""Mesh files: OBJ, OFF and PLY with polygon faces, float64, indices kept.

Readers: OBJ through meshio and PLY through plyfile, both maintained and both
keep the file's vertex numbering and polygon faces. OFF has no maintained
reader that does (meshio's reads triangles only, trimesh's triangulates,
off-rs parses to float32), so :func:`_read_off` is a short vectorized reader
of the OFF header, vertex rows and face rows.

Every reader hands its arrays to :meth:`Mesh.from_flat`, so a broken file
raises :class:`topomesh.MeshError` naming the face or vertex.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Union

import numpy as np

from topomesh._core import Mesh, MeshError

if TYPE_CHECKING:
    PathLike = Union[str, os.PathLike]

FORMATS = (".obj", ".off", ".ply")


def _suffix(path: PathLike) -> str:
    s = Path(path).suffix.lower()
    if s not in FORMATS:
        raise MeshError(f"{os.fspath(path)}: unsupported extension {s!r} (use one of {', '.join(FORMATS)})")
    return s


def load(path: PathLike, close_boundaries: bool = False, allow_multi_edges: bool = False) -> Mesh:
    """Read a polygon mesh from an OBJ, OFF or PLY file.

    Parameters
    ----------
    path : str or os.PathLike
        The file; its extension selects the format.
    close_boundaries, allow_multi_edges : bool
        As in :meth:`Mesh.from_polygons`. Files written by :meth:`Mesh.save`
        from a mesh with multi-edges need ``allow_multi_edges=True``.

    Raises
    ------
    MeshError
        Unsupported extension, unreadable file, or invalid mesh (the message
        names the face or vertex).
    """
    kind = _suffix(path)
    if not Path(path).is_file():
        raise MeshError(f"{os.fspath(path)}: no such file")
    try:
        if kind == ".obj":
            verts, sizes, idx = _read_obj(path)
        elif kind == ".ply":
            verts, sizes, idx = _read_ply(path)
        else:
            verts, sizes, idx = _read_off(path)
    except MeshError:
        raise
    except Exception as e:  # parser errors of any kind become MeshError
        raise MeshError(f"{os.fspath(path)}: cannot read {kind[1:].upper()} file ({type(e).__name__}: {e})") from e
    return Mesh.from_flat(verts, sizes, idx, close_boundaries=close_boundaries, allow_multi_edges=allow_multi_edges)


def save(mesh: Mesh, path: PathLike) -> None:
    """Write ``mesh`` to an OBJ, OFF or PLY file (polygon faces, float64
    coordinates written with 17 significant digits, so reading it back gives
    the same vertices bit for bit). Hole faces are not written."""
    kind = _suffix(path)
    if kind == ".ply":
        _write_ply(path, mesh.vertices, mesh.face_sizes, mesh.face_indices)
    else:
        mesh._write_text(os.fspath(path), kind[1:])


def _read_obj(path: PathLike):
    import meshio

    m = meshio.read(os.fspath(path), file_format="obj")
    blocks = [c.data for c in m.cells]
    sizes = np.concatenate([np.full(len(b), b.shape[1], dtype=np.int64) for b in blocks]) if blocks else np.zeros(0, np.int64)
    idx = np.concatenate([b.reshape(-1) for b in blocks]).astype(np.int64) if blocks else np.zeros(0, np.int64)
    return np.asarray(m.points, dtype=np.float64)[:, :3], sizes, idx


def _read_ply(path: PathLike):
    from plyfile import PlyData

    ply = PlyData.read(os.fspath(path))
    v = ply["vertex"]
    verts = np.column_stack([np.asarray(v[c], dtype=np.float64) for c in ("x", "y", "z")])
    face = ply["face"]
    name = "vertex_indices" if "vertex_indices" in face.data.dtype.names else "vertex_index"
    lists = face[name]
    sizes = np.fromiter((len(x) for x in lists), dtype=np.int64, count=len(lists))
    idx = np.concatenate(list(lists)).astype(np.int64) if len(lists) else np.zeros(0, np.int64)
    return verts, sizes, idx


def _write_ply(path: PathLike, verts: np.ndarray, sizes: np.ndarray, idx: np.ndarray) -> None:
    from plyfile import PlyData, PlyElement

    vert = np.empty(len(verts), dtype=[("x", "f8"), ("y", "f8"), ("z", "f8")])
    vert["x"], vert["y"], vert["z"] = verts.T
    faces = np.empty(len(sizes), dtype=[("vertex_indices", "O")])
    faces["vertex_indices"] = np.split(idx.astype(np.int32), np.cumsum(sizes)[:-1]) if len(sizes) else []
    PlyData(
        [PlyElement.describe(vert, "vertex"), PlyElement.describe(faces, "face", val_types={"vertex_indices": "i4"})],
        text=False,
    ).write(os.fspath(path))


def _read_off(path: PathLike):
    with open(path, encoding="ascii", errors="replace") as f:
        rows = [ln.split("#", 1)[0].split() for ln in f]
    rows = [r for r in rows if r]
    if not rows or not rows[0][0].upper().endswith("OFF"):
        raise MeshError(f"{os.fspath(path)}: not an OFF file (first line {rows[0] if rows else ''!r})")
    head = rows[0][1:] if len(rows[0]) > 1 else rows[1]
    start = 1 if len(rows[0]) > 1 else 2
    nv, nf = int(head[0]), int(head[1])
    if len(rows) < start + nv + nf:
        raise MeshError(f"{os.fspath(path)}: header announces {nv} vertices and {nf} faces, file is shorter")
    verts = np.array([r[:3] for r in rows[start : start + nv]], dtype=np.float64).reshape(nv, 3)
    frows = rows[start + nv : start + nv + nf]
    sizes = np.array([int(r[0]) for r in frows], dtype=np.int64)
    for k, (r, s) in enumerate(zip(frows, sizes)):
        if len(r) < s + 1:
            raise MeshError(f"{os.fspath(path)}: face {k} announces {s} vertices but lists {len(r) - 1}")
    idx = np.array([int(x) for r, s in zip(frows, sizes) for x in r[1 : s + 1]], dtype=np.int64)
    return verts, sizes, idx
