"""PLY for :mod:`topomesh.io`: binary little-endian face records laid out
by the core (``_ply_write_records``) and read by the core: one column per
property gathered straight from the file (``_ply_gather_file``) when every
face has one size, else the whole file read (``_read_bytes``) and its records
walked (``_ply_split_records``); plyfile for ASCII and big-endian PLY. The layout
is described in the formats section of :mod:`topomesh.io`."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Union

import numpy as np

from topomesh._core import (
    Mesh,
    MeshError,
    _ply_gather,
    _ply_gather_file,
    _ply_split_records,
    _ply_write_records,
    _read_bytes,
)
from topomesh._fileattrs import _ply_fields

if TYPE_CHECKING:
    PathLike = Union[str, os.PathLike]


_PLY_INT = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
             "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4"}
_PLY_NUM = dict(_PLY_INT, float="f4", float32="f4", double="f8", float64="f8")


def _write_ply(tmp: str, mesh: Mesh, fields: tuple | None = None) -> None:
    """Binary little-endian PLY: the header here, the face records laid out
    by the core and appended to the file (``_ply_write_records``: plyfile
    writes list properties one face at a time, 25 s for 1M faces).
    ``fields`` is ``_ply_fields(None, mesh)`` when the caller has it already."""
    verts, sizes = mesh.vertices, mesh.face_sizes
    idx, twins = mesh.face_indices, mesh.corner_twins
    if len(verts) >= 2**31 or len(idx) >= 2**31:
        raise MeshError("PLY stores int32 indices: the mesh is too large (use .npz)")
    vextra, fextra, cextra, comments = fields if fields is not None else _ply_fields(None, mesh)
    top = int(sizes.max()) if len(sizes) else 0
    # (property, count type, value type, per-corner values (C, k)), then the face scalars
    # the int64 index columns as they are: the core narrows them to int32 (checked above to fit)
    lists = [(p, "uint" if top > 255 else "uchar", "int", np.ascontiguousarray(a, dtype="<i8")[:, None])
             for p, a in (("vertex_indices", idx), ("corner_twins", twins))]
    lists += [(p, "uint" if top * a.shape[1] > 255 else "uchar", "double", a.astype("<f8")) for p, a in cextra]
    header = ["ply", "format binary_little_endian 1.0",
              "comment written by topomesh; corner_twins: the twin corner of each corner, -1 at a boundary side, -2 at a point-sphere"]
    header += [f"comment {c}" for c in comments]
    header += [f"element vertex {len(verts)}"] + [f"property double {c}" for c in ["x", "y", "z"] + [p for p, _ in vextra]]
    header.append(f"element face {len(sizes)}")
    header += [f"property list {ct} {vt} {p}" for p, ct, vt, _ in lists[:2]]
    header += [f"property {t} {p}" for p, t, _ in fextra]
    header += [f"property list {ct} {vt} {p}" for p, ct, vt, _ in lists[2:]]
    header.append("end_header\n")
    sizes = np.ascontiguousarray(sizes, dtype=np.int64)
    vcols = [verts] + [np.asarray(c, dtype=np.float64)[:, None] for _, c in vextra]
    with open(tmp, "wb") as f:
        f.write("\n".join(header).encode("ascii"))
        # the vertex buffer as it is (a view of the mesh's float64 positions) when it has no extra columns
        f.write(verts if len(vcols) == 1 and verts.dtype == np.dtype("<f8") else np.ascontiguousarray(np.hstack(vcols), dtype="<f8"))
    # the face records, appended by the core chunk by chunk through two reused buffers, the
    # next chunk laid out while this one is written: a fresh buffer of the whole body (26 MB for
    # 1M triangles) cost more in page faults than laying the records out did
    cols = [(4 if ct == "uint" else 1, a_.shape[1], 4, 8, _raw(a_)) for _, ct, _, a_ in lists[:2]]
    cols += [(0, 1, np.asarray(x).dtype.itemsize, np.asarray(x).dtype.itemsize, _raw(np.asarray(x))) for _, _, x in fextra]
    cols += [(4 if ct == "uint" else 1, a_.shape[1], a_.dtype.itemsize, a_.dtype.itemsize, _raw(a_)) for _, ct, _, a_ in lists[2:]]
    _ply_write_records(tmp, sizes, cols)


def _raw(a):
    return np.ascontiguousarray(a).view(np.uint8).reshape(-1)


class _Source:
    """A PLY file, read as little as its layout needs: the header and the
    first face record by small reads; a uniform element's columns gathered
    by the core straight from the file (``_ply_gather_file``: chunks through
    two reused buffers, so the file's bytes take no fresh pages; reading a
    36 MiB file whole took 18-20 ms before its gather could start); the whole
    file (``_read_bytes``) only for what needs it: faces of several sizes or
    a header past the probe.
    A read-only memory map was tried for issue 19: fast on a file read
    twice, but 5-10x slower than a copy when the file had just been written,
    the usual save-then-load case: every page faulted in while the kernel
    was writing the file back."""

    def __init__(self, path: PathLike):
        self.path = os.fspath(path)
        self._data = None
        try:
            with open(self.path, "rb") as f:
                self.size = os.fstat(f.fileno()).st_size
                self.head = f.read(_HEADER_PROBE)
        except OSError as e:
            raise MeshError(f"{self.path}: cannot read ({e.strerror})") from None

    def data(self) -> np.ndarray:
        """The whole file as uint8, read once."""
        if self._data is None:
            self._data = _read_bytes(self.path)
        return self._data

    def at(self, pos: int, n: int) -> bytes:
        """``n`` bytes from byte ``pos`` (fewer at the end of the file)."""
        if self._data is not None:
            return bytes(self._data[pos : pos + n])
        if pos + n <= len(self.head):
            return self.head[pos : pos + n]
        try:
            with open(self.path, "rb") as f:
                f.seek(pos)
                return f.read(n)
        except OSError as e:
            raise MeshError(f"{self.path}: cannot read ({e.strerror})") from None

    def gather(self, start: int, n: int, record: int, fields: list) -> list:
        if self._data is not None:
            return _ply_gather(self._data, start, n, record, fields)
        return _ply_gather_file(self.path, start, n, record, fields)


def _read_ply(path: PathLike):
    """``(vertices, sizes, indices, twins or None, (vertex properties, face
    properties, list property names, comments))``: binary little-endian files
    with the core (one column per property when every face has one size,
    else the core's record walk), ASCII and big-endian ones with plyfile."""
    src = _Source(path)
    head = _binary_header(src)
    if head is not None:
        fast = _read_uniform(src, *head)
        if fast is None:
            try:
                fast = _read_split(src, *head)
            except MeshError as e:
                raise MeshError(f"{os.fspath(path)}: {e}") from None
        if fast is not None:
            return fast
    from plyfile import PlyData

    ply = PlyData.read(os.fspath(path))
    v = ply["vertex"]
    verts = np.column_stack([np.asarray(v[c], dtype=np.float64) for c in ("x", "y", "z")]).reshape(-1, 3)
    vprops = {p.name: np.asarray(v[p.name]) for p in v.properties}
    face = ply["face"]
    names = [p.name for p in face.properties]
    name = "vertex_indices" if "vertex_indices" in names else "vertex_index"
    lists = face[name]
    sizes = np.fromiter((len(x) for x in lists), dtype=np.int64, count=len(lists))
    flat = lambda ls: np.concatenate(list(ls)) if len(ls) else np.zeros(0)  # noqa: E731
    list_names = {p.name for p in face.properties if hasattr(p, "len_dtype")}
    fprops = {p: flat(face[p]) if p in list_names else np.asarray(face[p]) for p in names}
    twins = fprops["corner_twins"].astype(np.int64) if "corner_twins" in names else None
    idx = fprops[name].astype(np.int64)
    return verts, sizes, idx, twins, (vprops, fprops, list_names, list(ply.comments))


def _read_ply_uniform(path: PathLike):
    """The one-gather read of a binary little-endian PLY whose faces
    all have one size, ``None`` for any other file (see :func:`_read_uniform`)."""
    src = _Source(path)
    head = _binary_header(src)
    return None if head is None else _read_uniform(src, *head)


#: Bytes searched for the end of a PLY header before the whole file is.
_HEADER_PROBE = 1 << 16


def _binary_header(src: _Source):
    """``(body offset, vertex count, vertex properties, face count, face
    properties, comments)`` of a binary little-endian PLY with a vertex
    element of scalar properties (``x y z`` among them) followed by a face
    element with ``vertex_indices``; properties as ``(name, count dtype or
    None, value dtype)``. ``None`` for anything else (plyfile reads it)."""
    head = src.head
    if head[:4] != b"ply\n":
        return None
    end = head.find(b"end_header\n")
    if end < 0 and src.size > len(head):
        head = bytes(src.data())  # a header longer than the probe (many comments): rare
        end = head.find(b"end_header\n")
    if end < 0:
        return None
    lines = head[:end].decode("ascii", "replace").splitlines()[1:]
    comments = [ln.split(None, 1)[1] if len(ln.split(None, 1)) > 1 else "" for ln in lines if ln.split()[:1] == ["comment"]]
    rows = [r for r in (ln.split() for ln in lines) if r and r[0] not in ("comment", "obj_info")]
    try:
        if rows[0][1:] != ["binary_little_endian", "1.0"]:
            return None
        elements = []
        for r in rows[1:]:
            if r[0] == "element":
                elements.append((r[1], int(r[2]), []))
            elif r[0] == "property" and r[1] == "list":
                elements[-1][2].append((r[4], _PLY_INT[r[2]], _PLY_NUM[r[3]]))
            elif r[0] == "property":
                elements[-1][2].append((r[2], None, _PLY_NUM[r[1]]))
            else:
                return None
        (vname, nv, vprops), (fname, nf, fprops) = elements
    except (ValueError, IndexError, KeyError):
        return None
    if (vname, fname) != ("vertex", "face") or any(c is not None for _, c, _ in vprops) or nf == 0:
        return None
    if "vertex_indices" not in [p for p, _, _ in fprops] or not {"x", "y", "z"} <= {p for p, _, _ in vprops}:
        return None
    return end + len(b"end_header\n"), nv, vprops, nf, fprops, comments


def _vertex_dtype(vprops: list) -> np.dtype:
    return np.dtype([(p, np.dtype(t).newbyteorder("<")) for p, _, t in vprops])


def _vertex_columns(src: _Source, body: int, nv: int, vprops: list):
    vdt = _vertex_dtype(vprops)
    if src.size < body + nv * vdt.itemsize:
        return None, None, vdt
    names = vdt.names
    t = vdt["x"]
    if names[:3] == ("x", "y", "z") and vdt["y"] == t and vdt["z"] == t and t in (np.dtype("<f8"), np.dtype("<f4")):
        # x y z as one column of the core's gather (float64: every file topomesh writes;
        # float32: trimesh's, most scanners'), the other properties beside it
        rest = names[3:]
        cols = src.gather(body, nv, vdt.itemsize, [(0, 3 * t.itemsize)] + [(vdt.fields[p][1], vdt[p].itemsize) for p in rest])
        verts = cols[0].view(t).reshape(nv, 3)
        if t != np.dtype("<f8"):
            verts = verts.astype(np.float64)
        other = dict(zip(rest, cols[1:]))
    else:
        # any other layout: one gathered column per property, x y z converted to float64
        cols = src.gather(body, nv, vdt.itemsize, [(vdt.fields[p][1], vdt[p].itemsize) for p in names])
        other = dict(zip(names, cols))
        verts = np.empty((nv, 3), np.float64)
        for j, c in enumerate("xyz"):
            verts[:, j] = other.pop(c).view(vdt[c])
    # x, y, z as views of the float64 positions, the others in the file's types
    props = {p: verts[:, "xyz".index(p)] if p in ("x", "y", "z") else other[p].view(vdt[p]) for p in names}
    return verts, props, vdt


def _read_uniform(src: _Source, body: int, nv: int, vprops: list, nf: int, fprops: list, comments: list):
    """Faces that all have one size: one gathered column per property; ``None``
    when the face records differ in length."""
    fstart = body + nv * _vertex_dtype(vprops).itemsize
    # the list lengths of the first face fix the record layout
    fields, pos = [], fstart
    for p, c, t in fprops:
        t = np.dtype(t).newbyteorder("<")
        if c is None:
            fields.append((p, t))
            pos += t.itemsize
            continue
        c = np.dtype(c).newbyteorder("<")
        if pos + c.itemsize > src.size:
            return None
        k = int(np.frombuffer(src.at(pos, c.itemsize), c)[0])
        if k < 0:
            return None
        fields += [("\0n" + p, c), (p, t, (k,))]
        pos += c.itemsize + k * t.itemsize
    fdt = np.dtype(fields)
    if src.size != fstart + nf * fdt.itemsize:
        return None
    # every field's column in one parallel pass each (the core's gather), as flat arrays
    names = fdt.names
    cols = src.gather(fstart, nf, fdt.itemsize, [(fdt.fields[q][1], fdt[q].itemsize) for q in names])
    faces = {q: a.view(fdt[q].base) for q, a in zip(names, cols)}
    for p, c, _ in fprops:
        if c is not None and not (faces["\0n" + p] == fdt[p].shape[0]).all():
            return None
    k = fdt["vertex_indices"].shape[0]
    if k == 0:
        return None
    verts, vp, _ = _vertex_columns(src, body, nv, vprops)
    # int32 index columns (as topomesh writes them) stay int32, which Mesh.from_flat
    # reads without an int64 copy (48 MB fewer fresh pages for 1M triangles); other
    # types become int64
    idx = _index_column(faces["vertex_indices"])
    twins = _index_column(faces["corner_twins"]) if "corner_twins" in names else None
    fp = {p: idx if p == "vertex_indices" else twins if p == "corner_twins" else faces[p] for p, c, _ in fprops}
    lists = {p for p, c, _ in fprops if c is not None}
    return verts, np.full(nf, k, np.int64), idx, twins, (vp, fp, lists, comments)


def _index_column(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.int32 if a.dtype == np.dtype("<i4") else np.int64).reshape(-1)


def _read_split(src: _Source, body: int, nv: int, vprops: list, nf: int, fprops: list, comments: list):
    """Faces of several sizes: the core walks the records once and hands back
    one column per property (1M mixed faces in ~0.1 s, where plyfile's
    per-face decoding took ~20 s). ``None`` when the file is shorter than its
    vertex element."""
    data = src.data()  # the record walk needs the whole file
    verts, vp, vdt = _vertex_columns(src, body, nv, vprops)
    if verts is None:
        return None
    spec = [(0 if c is None else np.dtype(c).itemsize, c is not None and np.dtype(c).kind == "i", np.dtype(t).itemsize)
            for _, c, t in fprops]
    values, counts, end = _ply_split_records(data, body + nv * vdt.itemsize, nf, spec, "face")
    if end != len(data):
        raise MeshError(f"PLY face element: {len(data) - end} bytes after the last face record")
    fp = {p: v.view(np.dtype(t).newbyteorder("<")) for (p, _, t), v in zip(fprops, values)}
    lists = {p for p, c, _ in fprops if c is not None}
    cnt = dict(zip([p for p, _, _ in fprops], counts))
    sizes = cnt["vertex_indices"]
    if sizes is None:
        return None
    if "corner_twins" in cnt and not np.array_equal(cnt["corner_twins"], sizes):
        raise MeshError("PLY face element: corner_twins lists differ in length from vertex_indices")
    twins = fp["corner_twins"].astype(np.int64) if "corner_twins" in fp else None
    idx = fp["vertex_indices"].astype(np.int64)
    return verts, sizes, idx, twins, (vp, fp, lists, comments)
