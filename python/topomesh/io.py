"""Mesh files: the lossless ``.npz`` and ``.ply``, and OBJ and OFF.

Formats
-------
``.npz`` (native)
    ``numpy.savez`` of ``vertices``, ``face_sizes``, ``face_indices``,
    ``corner_twins`` and ``format_version`` (1): every mesh comes back equal,
    self-loops, multi-edges, two-gons, point-spheres and hole faces included.
``.ply``
    Binary little-endian PLY: float64 ``x y z``, a ``vertex_indices`` int32
    list per face and an extra ``corner_twins`` int32 list per face (other
    readers ignore it), so it is lossless too. Written with NumPy; read with
    NumPy when every face has one size, else through plyfile (any PLY; one
    without ``corner_twins`` is read as a polygon list).
``.obj``, ``.off``
    Polygon lists: they cannot say which sides of a multi-edge or which
    self-loops form an edge. :func:`save` writes a mesh only when reading the
    list back (with ``allow_multi_edges=True``) gives the same mesh, and
    otherwise raises :class:`MeshError` naming ``.npz``/``.ply``. Hole faces
    are not written: the file holds the open mesh, which loads with
    ``close_boundaries=True``. OBJ is read by the core's reader
    (``topomesh._core._read_obj``: negative indices, ``v/vt/vn`` with their
    own counts, groups, materials, continuations, CRLF; ``l`` and ``p``
    elements are skipped with a :class:`GeometryWarning` giving their count).
    OFF has no maintained reader that keeps polygons as float64 (meshio's
    reads triangles only, trimesh's triangulates, off-rs parses to float32),
    so :func:`_read_off` is a short reader of the header, vertex and face rows.

Saving is atomic: the file is written beside the target under a temporary
name and renamed over it, so a failed save leaves any existing file as it was.
Every failure, reading or writing, is a :class:`MeshError` naming the path.
"""

from __future__ import annotations

import os
import tempfile
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Union

import numpy as np

from topomesh._core import GeometryWarning, Mesh, MeshError, _read_obj

if TYPE_CHECKING:
    PathLike = Union[str, os.PathLike]

#: Formats :func:`save` writes (the first two are lossless for every mesh).
SAVE_FORMATS = (".npz", ".ply", ".obj", ".off")
#: Version of the ``.npz`` layout written by :func:`save`.
NPZ_VERSION = 1
_NPZ_KEYS = ("vertices", "face_sizes", "face_indices", "corner_twins")


def read_formats() -> tuple:
    """Extensions :func:`load` reads: the saved formats and ``.stl``."""
    return SAVE_FORMATS + (".stl",)


def _suffix(path: PathLike, formats: tuple) -> str:
    s = Path(path).suffix.lower()
    if s not in formats:
        raise MeshError(f"{os.fspath(path)}: unsupported extension {s!r} (use one of {', '.join(formats)})")
    return s


def _from_state(vertices, face_sizes, face_indices, corner_twins) -> Mesh:
    """Unpickling: the exact rebuild of :meth:`Mesh.from_flat` with twins."""
    return Mesh.from_flat(vertices, face_sizes, face_indices, twins=corner_twins)


def load(path: PathLike, close_boundaries: bool = False, allow_multi_edges: bool = False, repair: bool = False) -> Mesh:
    """Read a mesh from a ``.npz``, ``.ply``, ``.obj`` or ``.off`` file.

    Parameters
    ----------
    path : str or os.PathLike
        The file; its extension selects the format.
    close_boundaries, allow_multi_edges : bool
        As in :meth:`Mesh.from_polygons`, for files without ``corner_twins``
        (OBJ, OFF, foreign PLY); ``.npz`` and topomesh's PLY are rebuilt
        exactly and need neither.
    repair : bool, default False
        Run the file's polygons through :func:`topomesh.repair`
        (merge coincident vertices, drop degenerate faces, orient) instead of
        building them as they are.

    Raises
    ------
    MeshError
        Naming the path: unsupported extension, missing or unreadable file,
        malformed content (OBJ errors give the line), or an invalid mesh (the
        message names the face or vertex).

    Warns
    -----
    GeometryWarning
        An OBJ file with ``l`` (polyline) or ``p`` (point) elements: they are
        not faces and are skipped; the warning gives their count.
    """
    kind = _suffix(path, read_formats())
    name = os.fspath(path)
    if not Path(path).is_file():
        raise MeshError(f"{name}: no such file")
    twins = None
    try:
        if kind == ".npz":
            verts, sizes, idx, twins = _read_npz(path)
        elif kind == ".ply":
            verts, sizes, idx, twins = _read_ply(path)
        elif kind == ".obj":
            verts, sizes, idx, n_lines, n_points = _read_obj(name)
            if n_lines or n_points:
                warnings.warn(
                    f"{name}: skipped {n_lines} polyline (l) and {n_points} point (p) elements: they are not faces",
                    GeometryWarning,
                    stacklevel=2,
                )
        elif kind == ".stl":
            from topomesh.stl import read_stl  # welds exact duplicates, as STL repeats every corner

            verts, tris = read_stl(path)
            sizes = np.full(len(tris), 3, dtype=np.int64)
            idx = np.asarray(tris, dtype=np.int64).reshape(-1)
        else:
            verts, sizes, idx = _read_off(path)
    except MeshError:
        raise
    except OSError as e:
        raise MeshError(f"{name}: cannot read ({e.strerror or e})") from e
    except Exception as e:  # parser errors of any kind become MeshError
        raise MeshError(f"{name}: cannot read {kind[1:].upper()} file ({type(e).__name__}: {e})") from e
    try:
        if repair:
            from topomesh._repair import repair_flat

            mesh, _report = repair_flat(verts, sizes, idx, close_boundaries=close_boundaries)
            return mesh
        if twins is not None:
            return Mesh.from_flat(verts, sizes, idx, twins=twins)
        return Mesh.from_flat(verts, sizes, idx, close_boundaries=close_boundaries, allow_multi_edges=allow_multi_edges)
    except MeshError as e:
        raise MeshError(f"{name}: {e}") from None


def save(mesh: Mesh, path: PathLike) -> None:
    """Write ``mesh`` to a ``.npz``, ``.ply``, ``.obj`` or ``.off`` file.

    Coordinates are written exactly (binary float64, or the shortest decimal
    that reads back to the same bits). ``.npz`` and ``.ply`` keep every mesh;
    ``.obj`` and ``.off`` keep the polygons only (see the module docs). The
    file is replaced atomically: on any failure the old file is untouched and
    no temporary file is left.

    Raises
    ------
    MeshError
        Naming the path: unsupported extension, a mesh that OBJ/OFF cannot
        represent (self-loops or multi-edges that a polygon list pairs
        differently), or any I/O failure (missing directory, permission, disk
        full, file size limit).
    """
    kind = _suffix(path, SAVE_FORMATS)
    name = os.fspath(path)
    if kind in (".obj", ".off") and not mesh._polygons_are_lossless():
        raise MeshError(
            f"{name}: {kind[1:].upper()} stores a polygon list, which pairs this mesh's multi-edges or self-loops "
            "differently (it would not load back equal); save it as .npz or .ply, which store corner_twins"
        )
    if kind == ".npz":
        _atomic_write(path, lambda tmp: _write_npz(tmp, mesh))
    elif kind == ".ply":
        _atomic_write(path, lambda tmp: _write_ply(tmp, mesh))
    else:
        _atomic_write(path, lambda tmp: mesh._write_text(tmp, kind[1:]))


def _umask() -> int:
    old = os.umask(0o022)
    os.umask(old)
    return old


_UMASK = _umask()


def _atomic_write(path: PathLike, write: Callable[[str], None]) -> None:
    """Run ``write(tmp)`` on a temporary file beside ``path``, then rename it
    over ``path``; on any failure remove the temporary file and leave ``path``
    as it was. I/O errors become :class:`MeshError` naming ``path``."""
    target = Path(path)
    name = os.fspath(path)
    try:
        fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as e:
        raise MeshError(f"{name}: cannot write ({e.strerror or e})") from e
    os.close(fd)
    try:
        write(tmp)
        try:
            mode = target.stat().st_mode & 0o7777
        except OSError:
            mode = 0o666 & ~_UMASK
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException as e:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(e, MeshError):
            raise MeshError(f"{name}: cannot write ({str(e).replace(tmp, name)})") from None
        if isinstance(e, OSError):
            raise MeshError(f"{name}: cannot write ({e.strerror or e})") from e
        raise


def _write_npz(tmp: str, mesh: Mesh) -> None:
    with open(tmp, "wb") as f:  # a file object: savez would append ".npz" to a name
        np.savez(
            f,
            format_version=np.int64(NPZ_VERSION),
            vertices=mesh.vertices,
            face_sizes=mesh.face_sizes,
            face_indices=mesh.face_indices,
            corner_twins=mesh.corner_twins,
        )


def _read_npz(path: PathLike):
    with np.load(os.fspath(path), allow_pickle=False) as z:
        missing = [k for k in ("format_version",) + _NPZ_KEYS if k not in z.files]
        if missing:
            raise MeshError(f"{os.fspath(path)}: not a topomesh .npz file (missing {', '.join(missing)})")
        version = int(z["format_version"])
        if version > NPZ_VERSION:
            raise MeshError(f"{os.fspath(path)}: .npz format version {version} is newer than this topomesh reads ({NPZ_VERSION})")
        return tuple(z[k] for k in _NPZ_KEYS)


_PLY_INT = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
             "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4"}


def _write_ply(tmp: str, mesh: Mesh) -> None:
    """Binary little-endian PLY, the face records laid out with NumPy (plyfile
    writes list properties one face at a time: 25 s for 1M faces)."""
    verts, sizes = mesh.vertices, mesh.face_sizes
    idx, twins = mesh.face_indices, mesh.corner_twins
    if len(verts) >= 2**31 or len(idx) >= 2**31:
        raise MeshError("PLY stores int32 indices: the mesh is too large (use .npz)")
    wide = len(sizes) > 0 and int(sizes.max()) > 255
    count, cs = ("uint", 4) if wide else ("uchar", 1)
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        "comment written by topomesh; corner_twins: the twin corner of each corner, -1 at a boundary side, -2 at a point-sphere\n"
        f"element vertex {len(verts)}\nproperty double x\nproperty double y\nproperty double z\n"
        f"element face {len(sizes)}\nproperty list {count} int vertex_indices\nproperty list {count} int corner_twins\n"
        "end_header\n"
    ).encode("ascii")
    rec = 2 * cs + 8 * sizes
    start = np.zeros(len(sizes), dtype=np.int64)
    np.cumsum(rec[:-1], out=start[1:])
    buf = np.empty(int(rec.sum()), dtype=np.uint8)
    cnt = sizes.astype("<u4" if wide else "u1").view(np.uint8).reshape(-1, cs)
    lanes = np.arange(cs)
    buf[(start[:, None] + lanes)] = cnt
    buf[(start + cs + 4 * sizes)[:, None] + lanes] = cnt
    face_start = np.repeat(start, sizes)
    local = np.arange(len(idx)) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    four = np.arange(4)
    dest = face_start + cs + 4 * local
    buf[dest[:, None] + four] = idx.astype("<i4").view(np.uint8).reshape(-1, 4)
    dest += cs + 4 * np.repeat(sizes, sizes)
    buf[dest[:, None] + four] = twins.astype("<i4").view(np.uint8).reshape(-1, 4)
    with open(tmp, "wb") as f:
        f.write(header)
        f.write(np.ascontiguousarray(verts, dtype="<f8").tobytes())
        f.write(buf.tobytes())


def _read_ply(path: PathLike):
    fast = _read_ply_uniform(path)
    if fast is not None:
        return fast
    from plyfile import PlyData

    ply = PlyData.read(os.fspath(path))
    v = ply["vertex"]
    verts = np.column_stack([np.asarray(v[c], dtype=np.float64) for c in ("x", "y", "z")]).reshape(-1, 3)
    face = ply["face"]
    names = face.data.dtype.names or ()
    name = "vertex_indices" if "vertex_indices" in names else "vertex_index"
    lists = face[name]
    sizes = np.fromiter((len(x) for x in lists), dtype=np.int64, count=len(lists))
    flat = lambda ls: np.concatenate(list(ls)).astype(np.int64) if len(ls) else np.zeros(0, np.int64)  # noqa: E731
    twins = flat(face["corner_twins"]) if "corner_twins" in names else None
    return verts, sizes, flat(lists), twins


def _read_ply_uniform(path: PathLike):
    """The layout :func:`_write_ply` writes, when every face has one size:
    read with one ``np.frombuffer``. ``None`` for anything else (plyfile
    reads it, one face at a time)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\n") or end < 0:
        return None
    lines = [ln.split() for ln in data[:end].decode("ascii", "replace").splitlines()[1:]]
    lines = [ln for ln in lines if ln and ln[0] != "comment"]
    try:
        (fmt, vel, x, y, z, fel, l1, l2) = lines
        nv, nf = int(vel[2]), int(fel[2])
        ok = (
            fmt[1:] == ["binary_little_endian", "1.0"]
            and vel[:2] == ["element", "vertex"] and fel[:2] == ["element", "face"]
            and [x, y, z] == [["property", "double", c] for c in "xyz"]
            and l1[:2] == l2[:2] == ["property", "list"] and l1[2] == l2[2] and l1[2] in _PLY_INT
            and l1[3] == l2[3] == "int" and l1[4] == "vertex_indices" and l2[4] == "corner_twins"
        )
    except (ValueError, IndexError):
        return None
    if not ok:
        return None
    body = end + len(b"end_header\n")
    cdt = np.dtype(_PLY_INT[l1[2]]).newbyteorder("<")
    fbytes = len(data) - body - 24 * nv
    if nf == 0 or fbytes < 0:
        return None
    k = int(np.frombuffer(data, cdt, 1, body + 24 * nv)[0])
    if k <= 0 or fbytes != nf * (2 * cdt.itemsize + 8 * k):
        return None
    rec = np.dtype([("n1", cdt), ("idx", "<i4", (k,)), ("n2", cdt), ("tw", "<i4", (k,))])
    faces = np.frombuffer(data, rec, nf, body + 24 * nv)
    if not ((faces["n1"] == k).all() and (faces["n2"] == k).all()):
        return None
    verts = np.frombuffer(data, "<f8", 3 * nv, body).reshape(nv, 3).astype(np.float64)
    return verts, np.full(nf, k, np.int64), faces["idx"].reshape(-1).astype(np.int64), faces["tw"].reshape(-1).astype(np.int64)


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
