"""Mesh files: the lossless ``.npz`` and ``.ply``, OBJ and OFF, and the
printers' STL and 3MF.

Formats
-------
``.npz`` (native)
    ``numpy.savez`` of ``vertices``, ``face_sizes``, ``face_indices``,
    ``corner_twins`` and ``format_version`` (1): every mesh comes back equal,
    self-loops, multi-edges, two-gons, point-spheres and hole faces included.
``.ply``
    Binary little-endian PLY: float64 ``x y z``, a ``vertex_indices`` int32
    list per face and an extra ``corner_twins`` int32 list per face (other
    readers ignore it), so it is lossless too. Written with NumPy; binary
    little-endian files are read with NumPy (one ``frombuffer`` when every
    face has one size, else after the core's one-pass walk of the face
    records), ASCII and big-endian ones through plyfile (any PLY; one without
    ``corner_twins`` is read as a polygon list).
``.obj``, ``.off``
    Polygon lists: they cannot say which sides of a multi-edge or which
    self-loops form an edge. :func:`save` writes a mesh only when reading the
    list back (with ``allow_multi_edges=True``) gives the same mesh, and
    otherwise raises :class:`MeshError` naming ``.npz``/``.ply``. Hole faces
    are not written: the file holds the open mesh, which loads back open
    (the default ``boundaries="keep"``). OBJ is read by the core's reader
    (``topomesh._core._read_obj``: negative indices, ``v/vt/vn`` with their
    own counts, groups, materials, continuations, CRLF; ``l`` and ``p``
    elements are skipped with a :class:`GeometryWarning` giving their count).
    OFF has no maintained reader that keeps polygons as float64 (meshio's
    reads triangles only, trimesh's triangulates, off-rs parses to float32),
    so :func:`_read_off` is a short reader of the header, vertex and face rows.
``.stl``, ``.3mf``
    Triangle meshes for printers, slicers and CAD: the triangles of
    :meth:`Mesh.triangulate` (with the points it adds), so the polygon faces,
    the hole faces and the corner twins are not kept and a file loads back as
    the triangle mesh (exact duplicate corners welded). STL is binary:
    an 80-byte header that never starts with ``solid`` (readers take such
    files for ASCII), float32 corners (coordinates are rounded) and facet
    normals computed from the triangles, written with NumPy; it is read by
    :func:`topomesh.stl.read_stl` (binary or ASCII). 3MF is written and
    read by trimesh (``trimesh.exchange.threemf``, which needs lxml and
    networkx: ``pip install 'topomesh[print]'``), with exact float64
    coordinates, in millimetres (3MF's unit). Since printers need a closed
    surface, :func:`save` warns (:class:`GeometryWarning`) when the
    triangles written are not a closed, consistently oriented 2-manifold:
    a mesh with holes, self-loops, one- or two-gons or vertices repeated in
    a face (the triangles pinch there, as in raw Sierpinski polyhedra), or
    vertices that coincide (after rounding to float32 for STL).
    See :func:`topomesh.printing.printable` for a full check.

Attributes and creases
----------------------
What each format keeps of :meth:`Mesh.with_attributes` and
:meth:`Mesh.with_creases` (every format also loads what it keeps):

``.npz``
    Everything: optional entries ``vertex_attr__<name>``,
    ``face_attr__<name>`` (any dtype but object, which needs pickle: left
    out with a :class:`GeometryWarning`), ``corner_attr__<name>`` (per
    corner), ``corner_sharpness`` (the sharpness of the edge leaving each
    corner: edge ids are renumbered by a rebuild, corners are not) and
    ``vertex_sharpness``. ``format_version`` stays 1: the entries are
    optional, and older readers ignore them.
``.ply``
    Numeric data as properties, named for other readers: a vertex
    attribute becomes float64 vertex properties ``<name>`` (k = 1) or
    ``<name>_0 .. <name>_{k-1}``, except ``"color"``/``"colour"`` with 3 or
    4 columns (``red green blue [alpha]``, still float64: the values are
    kept as they are) and ``"normal"``/``"normals"`` with 3 (``nx ny nz``);
    a face attribute face properties of its dtype (``<name>`` or
    ``<name>_j`` over its flattened trailing axes; int64 as PLY's int when it
    fits, else double when exact; bool as uchar); a corner attribute one
    per-face list of float64 with its k values per corner interleaved,
    ``texcoord`` for a 2-column ``"uv"`` (the name MeshLab reads); creases a
    vertex ``sharpness`` property and a ``corner_sharpness`` face list. A
    ``comment topomesh-attribute <element> <name> <dtype> <shape>
    <properties>`` header line per attribute makes the reading exact (names,
    dtypes, shapes). Strings and names that are no PLY property name are
    left out with a :class:`GeometryWarning`. A PLY from another program
    gives ``red green blue [alpha]`` as ``"color"``, ``nx ny nz`` as
    ``"normal"``, its other numeric vertex and face properties under their
    names, a ``texcoord`` list of 2 values per corner as corner ``"uv"`` and
    other lists of one number per corner as corner attributes.
``.obj``
    ``vt`` and ``vn`` with the corners' ``f v/vt/vn`` indices become the
    corner attributes ``"uv"`` (k = the most components a ``vt`` has) and
    ``"normal"``, read as (table, index) so seams stay exactly as written
    (left out when some faces have no ``vt``/``vn``); ``g``/``o`` and
    ``usemtl`` become the face attributes ``"group"`` and ``"material"``:
    NumPy string arrays of each face's name (several ``g`` names joined by a
    space; ``""`` before the first statement). :func:`save` writes them
    back: a ``vt``/``vn`` table of the distinct values (corners that share a
    value share a row, so seams stay seams) and a ``g``/``usemtl`` line
    wherever the name changes; other attributes and creases are left out
    with a :class:`GeometryWarning`.
``.off``, ``.stl``, ``.3mf``
    Positions and faces only; saving a mesh with data warns.

``load(repair=True)`` renumbers vertices and faces (and keeps no map), so
it leaves a file's attributes and creases out.

Saving is atomic: the file is written beside the target under a temporary
name and renamed over it, so a failed save leaves any existing file as it was.
Every failure, reading or writing, is a :class:`MeshError` naming the path.
"""

from __future__ import annotations

import os
import stat
import tempfile
import threading
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Union

import numpy as np

from topomesh._core import GeometryWarning, Mesh, MeshError, _read_obj
from topomesh._fileattrs import (
    _Data,
    _npz_arrays,
    _npz_data,
    _obj_data,
    _obj_fields,
    _ply_data,
    _ply_fields,
    _warn_left_out,
    _write_obj,
)
from topomesh._ply import _read_ply, _read_ply_uniform, _write_ply  # noqa: F401  (tests patch io._write_ply)

if TYPE_CHECKING:
    PathLike = Union[str, os.PathLike]

#: Formats :func:`save` writes (the first two are lossless for every mesh;
#: ``.stl`` and ``.3mf`` keep the triangles only).
SAVE_FORMATS = (".npz", ".ply", ".obj", ".off", ".stl", ".3mf")
#: The triangle formats of printers.
TRIANGLE_FORMATS = (".stl", ".3mf")
#: Version of the ``.npz`` layout written by :func:`save`.
NPZ_VERSION = 1
_NPZ_KEYS = ("vertices", "face_sizes", "face_indices", "corner_twins")


def read_formats() -> tuple:
    """Extensions :func:`load` reads: every format :func:`save` writes."""
    return SAVE_FORMATS


def _suffix(path: PathLike, formats: tuple) -> str:
    s = Path(path).suffix.lower()
    if s not in formats:
        raise MeshError(f"{os.fspath(path)}: unsupported extension {s!r} (use one of {', '.join(formats)})")
    return s


def check_writable(path: PathLike) -> None:
    """Raise :class:`MeshError` naming ``path`` when :func:`save` could not
    write it: an extension it does not write, or a directory that is missing
    or not writable (a temporary file is made there and removed). The
    command line checks its output this way before a long computation."""
    _suffix(path, SAVE_FORMATS)
    os.unlink(_temp_beside(path))


def _temp_beside(path: PathLike) -> str:
    """A new empty temporary file in ``path``'s directory (where a save
    renames it over ``path``); an unwritable place is a :class:`MeshError`
    naming ``path``."""
    target = Path(path)
    try:
        fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as e:
        raise MeshError(f"{os.fspath(path)}: cannot write ({e.strerror or e})") from e
    os.close(fd)
    return tmp


def _from_state(vertices, face_sizes, face_indices, corner_twins, data=None) -> Mesh:
    """Unpickling: the exact rebuild of :meth:`Mesh.from_flat` with twins, and its creases and attributes."""
    m = Mesh.from_flat(vertices, face_sizes, face_indices, twins=corner_twins)
    if data is not None:
        corner_sharpness, vertex_sharpness, vertex, face, corner = data
        if corner_sharpness is not None:
            m = m._with_corner_sharpness(corner_sharpness, vertex_sharpness)
        m = m.with_attributes(vertex=vertex, face=face, corner=corner)
    return m


def load(
    path: PathLike,
    close_boundaries: bool | None = None,
    allow_multi_edges: bool = False,
    repair: bool = False,
    boundaries: str = "keep",
) -> Mesh:
    """Read a mesh from a ``.npz``, ``.ply``, ``.obj``, ``.off``, ``.stl`` or ``.3mf`` file.

    Open meshes (scans, terrain, a tube without caps) are read as they are
    and stay open: each boundary loop becomes a hole face, never written
    back, so saving gives the same open mesh.

    Parameters
    ----------
    path : str or os.PathLike
        The file; its extension selects the format.
    close_boundaries : bool or None, default None
        Legacy spelling of ``boundaries`` (``True``: keep, ``False``: refuse).
    allow_multi_edges : bool, default False
        As in :meth:`Mesh.from_polygons`, for files without ``corner_twins``
        (OBJ, OFF, STL, 3MF, foreign PLY); ``.npz`` and topomesh's PLY are
        rebuilt exactly and do not need it.
    boundaries : {"keep", "refuse"}, default "keep"
        ``"refuse"`` raises :class:`MeshError` for an open mesh (naming a
        boundary edge), in every format.
    repair : bool, default False
        Run the file's polygons through :func:`topomesh.repair`
        (merge coincident vertices, drop degenerate faces, orient) instead of
        building them as they are; the file's attributes and creases are
        then left out.

    Raises
    ------
    MeshError
        Naming the path: unsupported extension, missing or unreadable file,
        malformed content (OBJ errors give the line), or an invalid mesh (the
        message names the face or vertex); for 3MF, trimesh, lxml or networkx
        missing.

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
    data = _Data()
    try:
        if kind == ".npz":
            verts, sizes, idx, twins, data = _read_npz(path)
        elif kind == ".ply":
            verts, sizes, idx, twins, props = _read_ply(path)
            data = _ply_data(name, *props, len(idx))
        elif kind == ".obj":
            verts, sizes, idx, n_lines, n_points, extras = _read_obj(name)
            if n_lines or n_points:
                warnings.warn(
                    f"{name}: skipped {n_lines} polyline (l) and {n_points} point (p) elements: they are not faces",
                    GeometryWarning,
                    stacklevel=2,
                )
            data = _obj_data(name, extras)
        elif kind == ".stl":
            from topomesh.stl import read_stl  # welds exact duplicates, as STL repeats every corner

            verts, tris = read_stl(path)
            sizes = np.full(len(tris), 3, dtype=np.int64)
            idx = np.asarray(tris, dtype=np.int64).reshape(-1)
        elif kind == ".3mf":
            verts, idx = _read_3mf(path)
            sizes = np.full(len(idx) // 3, 3, dtype=np.int64)
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

            idx = np.asarray(idx, dtype=np.int64)  # a PLY file's int32 columns: repair's arithmetic wants int64
            mesh, _report = repair_flat(verts, sizes, idx, close_boundaries=close_boundaries, boundaries=boundaries)
            return mesh
        kw = dict(close_boundaries=close_boundaries, boundaries=boundaries)
        if twins is not None:
            mesh = Mesh.from_flat(verts, sizes, idx, twins=twins, **kw)
        else:
            mesh = Mesh.from_flat(verts, sizes, idx, allow_multi_edges=allow_multi_edges, **kw)
        return data.attach(mesh)
    except MeshError as e:
        raise MeshError(f"{name}: {e}") from None


def save(mesh: Mesh, path: PathLike) -> None:
    """Write ``mesh`` to a ``.npz``, ``.ply``, ``.obj``, ``.off``, ``.stl`` or ``.3mf`` file.

    Coordinates are written exactly (binary float64, or the shortest decimal
    that reads back to the same bits), except in STL (float32). ``.npz`` and
    ``.ply`` keep every mesh; ``.obj`` and ``.off`` keep the polygons only;
    ``.stl`` (binary) and ``.3mf`` keep the triangles of
    :meth:`Mesh.triangulate` (see the module docs). The file is replaced
    atomically: on any failure the old file is untouched and no temporary
    file is left. On Linux and macOS an old file of 4 MiB or more is freed
    by the kernel on a background thread after the save returns (it took
    16-25 ms of a 36 MiB save).

    Raises
    ------
    MeshError
        Naming the path: unsupported extension, a mesh that OBJ/OFF cannot
        represent (self-loops or multi-edges that a polygon list pairs
        differently), 3MF without trimesh, lxml or networkx (optional:
        ``pip install 'topomesh[print]'``), or any I/O failure (missing
        directory, permission, disk full, file size limit).

    Warns
    -----
    GeometryWarning
        STL or 3MF whose triangles are not a closed 2-manifold (holes,
        pinches, vertices that coincide once written): a printer's slicer
        would reject or misread it.
    """
    kind = _suffix(path, SAVE_FORMATS)
    name = os.fspath(path)
    if kind in (".obj", ".off") and not mesh._polygons_are_lossless():
        raise MeshError(
            f"{name}: {kind[1:].upper()} stores a polygon list, which pairs this mesh's multi-edges or self-loops "
            "differently (it would not load back equal); save it as .npz or .ply, which store corner_twins"
        )
    if kind == ".npz":
        _npz_arrays(name, mesh)  # warns (naming the path) about what it leaves out
        _atomic_write(path, lambda tmp: _write_npz(tmp, mesh))
    elif kind == ".ply":
        fields = _ply_fields(name, mesh)  # warns (naming the path) about what it leaves out
        _atomic_write(path, lambda tmp: _write_ply(tmp, mesh, fields))
    elif kind in TRIANGLE_FORMATS:
        write3 = _threemf_exporter(name) if kind == ".3mf" else None
        verts, tris, (sides, pinched) = mesh._print_triangles()
        if kind == ".stl":
            # checked before writing: float32 turns them into inf, a file no reader takes back
            big = np.flatnonzero(np.abs(verts).max(axis=1, initial=0.0) > np.finfo(np.float32).max) if len(verts) else []
            if len(big):
                v = int(big[0])
                raise MeshError(
                    f"{name}: STL stores float32 coordinates, and vertex {v} at {tuple(float(x) for x in verts[v])} lies "
                    f"beyond float32's range (±{float(np.finfo(np.float32).max):.4g}; {len(big)} such vertices); "
                    "save it as .ply, .npz or .obj (float64), or scale the mesh down"
                )
            _atomic_write(path, lambda tmp: _write_stl(tmp, verts, tris))
        else:
            _atomic_write(path, lambda tmp: _write_3mf(tmp, write3, verts, tris))
        _warn_unprintable(name, kind, mesh, verts, sides, pinched)
        if not _Data.of(mesh).empty():
            _warn_left_out(name, f"{kind[1:].upper()} stores triangles only", _Data.of(mesh).names())
    elif kind == ".obj":
        uv, normal, group, material = _obj_fields(name, mesh)
        if uv is None and normal is None and group is None and material is None:
            _atomic_write(path, lambda tmp: mesh._write_text(tmp, "obj"))
        else:
            _atomic_write(path, lambda tmp: _write_obj(tmp, mesh, uv, normal, group, material))
    else:
        if not _Data.of(mesh).empty():
            _warn_left_out(name, "OFF stores positions and polygons only", _Data.of(mesh).names())
        _atomic_write(path, lambda tmp: mesh._write_text(tmp, kind[1:]))


def _umask() -> int:
    old = os.umask(0o022)
    os.umask(old)
    return old


_UMASK = _umask()


#: Size from which the file a save replaces is released on a background thread.
_RELEASE_FROM = 1 << 22


def _hold_replaced(target: Path) -> int | None:
    """A read-only descriptor of the regular file of 4 MiB or more that a save
    is about to rename over (POSIX), or ``None``. While it is open the rename
    does not free the old file; the last close does, and
    :func:`_release_in_background` makes that close on another thread. Freeing
    a 36 MiB file's pages and blocks took 16-25 ms of every PLY save over it
    (ext4), against 1-2 ms for the rename with the file held."""
    if os.name != "posix":
        return None  # Windows cannot rename over an open file
    try:
        st = os.stat(target)
        if not stat.S_ISREG(st.st_mode) or st.st_size < _RELEASE_FROM:
            return None
        # non-blocking: never wait on a FIFO put there since the stat
        return os.open(target, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError:
        return None


def _release_in_background(fd: int | None) -> None:
    """Closes ``fd`` on a daemon thread (at once when no thread can start)."""
    if fd is None:
        return
    try:
        threading.Thread(target=os.close, args=(fd,), name="topomesh-release", daemon=True).start()
    except RuntimeError:  # interpreter shutting down
        os.close(fd)


def _atomic_write(path: PathLike, write: Callable[[str], None]) -> None:
    """Run ``write(tmp)`` on a temporary file beside ``path``, then rename it
    over ``path``; on any failure remove the temporary file and leave ``path``
    as it was. I/O errors become :class:`MeshError` naming ``path``."""
    target = Path(path)
    name = os.fspath(path)
    tmp = _temp_beside(path)
    try:
        write(tmp)
        try:
            mode = target.stat().st_mode & 0o7777
        except OSError:
            mode = 0o666 & ~_UMASK
        os.chmod(tmp, mode)
        old = _hold_replaced(target)
        try:
            os.replace(tmp, target)
        finally:
            _release_in_background(old)
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
    extra = _npz_arrays(None, mesh)
    with open(tmp, "wb") as f:  # a file object: savez would append ".npz" to a name
        np.savez(
            f,
            format_version=np.int64(NPZ_VERSION),
            vertices=mesh.vertices,
            face_sizes=mesh.face_sizes,
            face_indices=mesh.face_indices,
            corner_twins=mesh.corner_twins,
            **extra,
        )


def _read_npz(path: PathLike):
    with np.load(os.fspath(path), allow_pickle=False) as z:
        missing = [k for k in ("format_version",) + _NPZ_KEYS if k not in z.files]
        if missing:
            raise MeshError(f"{os.fspath(path)}: not a topomesh .npz file (missing {', '.join(missing)})")
        version = int(z["format_version"])
        if version > NPZ_VERSION:
            raise MeshError(f"{os.fspath(path)}: .npz format version {version} is newer than this topomesh reads ({NPZ_VERSION})")
        return tuple(z[k] for k in _NPZ_KEYS) + (_npz_data(z),)


# ------------------------------------------------------------- STL and 3MF


#: the 80-byte binary STL header; readers take a file starting with "solid"
#: for ASCII, so it must not
STL_HEADER = b"binary STL by topomesh (triangles of Mesh.triangulate, float32)".ljust(80, b" ")


def _write_stl(tmp: str, verts: np.ndarray, tris: np.ndarray) -> None:
    """Binary STL, one 50-byte record per triangle (the layout
    :mod:`topomesh.stl` reads); facet normals from the float64 corners."""
    from topomesh.stl import _RECORD

    if len(tris) >= 2**32:
        raise MeshError(f"binary STL counts triangles in a uint32: {len(tris)} triangles are too many (use .ply or .npz)")
    c = np.take(verts, tris, axis=0)  # (T, 3, 3) float64
    n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
    rec = np.empty(len(tris), dtype=_RECORD)
    rec["normal"] = n
    rec["corners"] = c
    rec["attr"] = 0
    with open(tmp, "wb") as f:
        f.write(STL_HEADER)
        f.write(np.uint32(len(tris)).astype("<u4").tobytes())
        f.write(rec.tobytes())


def _threemf_exporter(name: str):
    """trimesh's 3MF writer, or a MeshError naming what to install."""
    try:
        import lxml  # noqa: F401  trimesh's 3MF code needs both
        import networkx  # noqa: F401
        from trimesh.exchange.threemf import export_3MF
    except ImportError as e:
        raise MeshError(
            f"{name}: 3MF is written and read through trimesh, which needs lxml and networkx "
            f"({e.name or e} is not installed): pip install 'topomesh[print]' (or trimesh lxml networkx)"
        ) from None
    return export_3MF


def _write_3mf(tmp: str, export, verts: np.ndarray, tris: np.ndarray) -> None:
    import trimesh

    tm = trimesh.Trimesh(vertices=verts, faces=tris, process=False, validate=False)
    data = export(tm)
    with open(tmp, "wb") as f:
        f.write(data)


def _read_3mf(path: PathLike):
    """Every object of a 3MF file (its build transforms applied), through
    trimesh, as welded vertices and triangle indices."""
    name = os.fspath(path)
    _threemf_exporter(name)
    import trimesh

    with open(name, "rb") as f:
        loaded = trimesh.load(f, file_type="3mf", force="mesh", process=False)
    corners = np.asarray(loaded.vertices, dtype=np.float64)[np.asarray(loaded.faces, dtype=np.int64)].reshape(-1, 3)
    if not np.isfinite(corners).all():
        raise MeshError(f"{name}: non-finite vertex coordinate")
    verts, index = Mesh._weld(corners, 0.0)  # objects and repeated vertices share exact points
    return verts, index.astype(np.int64)


def _warn_unprintable(name: str, kind: str, mesh: Mesh, verts: np.ndarray, sides: int, pinched: int) -> None:
    """The GeometryWarning of :func:`save` for STL/3MF that do not hold a
    closed 2-manifold as written (unpaired triangle sides, pinched vertices)."""
    written = verts.astype(np.float32).astype(np.float64) if kind == ".stl" else verts
    merged = len(verts) - len(Mesh._weld(written, 0.0)[0])
    if not (sides or pinched or merged or mesh.n_holes):
        return
    what = []
    if mesh.n_holes:
        what.append(f"{mesh.n_holes} boundary loops")
    if sides:
        what.append(f"{sides} triangle sides without exactly one opposite side")
    if pinched:
        what.append(f"{pinched} pinched vertices where triangle fans touch at a point (self-loops)")
    if merged:
        coincide = "coincide in float32" if kind == ".stl" else "coincide"
        what.append(f"{merged} vertices that {coincide} with others and will be welded when read")
    warnings.warn(
        f"{name}: the {kind[1:].upper()} triangles are not a closed 2-manifold ({'; '.join(what)}); "
        "a slicer may reject the file (check with Mesh.printable)",
        GeometryWarning,
        stacklevel=3,
    )


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
