"""Creases and attributes in files (used by :mod:`topomesh.io`): what OBJ,
PLY and ``.npz`` hold of them and how they are laid out. See the formats
section of :mod:`topomesh.io`."""

from __future__ import annotations

import re
import warnings
from typing import Any

import numpy as np

from topomesh._core import GeometryWarning, Mesh, MeshError

class _Data:
    """Creases and attributes on their way between a mesh and a file:
    ``vertex``/``face``/``corner`` dicts as :meth:`Mesh.with_attributes`
    takes them, and the crease sharpness per exported corner and per vertex
    (``None`` without creases)."""

    def __init__(self, vertex=None, face=None, corner=None, corner_sharpness=None, vertex_sharpness=None):
        self.vertex, self.face, self.corner = dict(vertex or {}), dict(face or {}), dict(corner or {})
        self.corner_sharpness, self.vertex_sharpness = corner_sharpness, vertex_sharpness

    @classmethod
    def of(cls, mesh: Mesh) -> "_Data":
        # a mesh without a crease table skips building the per-corner column
        cs, vs = (mesh._corner_sharpness(), mesh.vertex_sharpness) if mesh._has_creases() else (None, None)
        creased = cs is not None and bool(np.any(cs) or np.any(vs))
        return cls(
            mesh.vertex_attributes, mesh.face_attributes, mesh.corner_attributes,
            cs if creased else None, vs if creased else None,
        )

    def empty(self) -> bool:
        return not (self.vertex or self.face or self.corner or self.corner_sharpness is not None)

    __bool__ = lambda self: not self.empty()  # noqa: E731

    def names(self) -> str:
        what = [f"{kind} attribute {n!r}" for kind, d in (("vertex", self.vertex), ("face", self.face), ("corner", self.corner)) for n in d]
        if self.corner_sharpness is not None:
            what.append("creases")
        return ", ".join(what)

    def attach(self, mesh: Mesh) -> Mesh:
        if self.corner_sharpness is not None or self.vertex_sharpness is not None:
            cs = self.corner_sharpness if self.corner_sharpness is not None else np.zeros(len(mesh.face_indices))
            vs = self.vertex_sharpness if self.vertex_sharpness is not None else np.zeros(mesh.n_vertices)
            mesh = mesh._with_corner_sharpness(np.asarray(cs, dtype=np.float64), np.asarray(vs, dtype=np.float64))
        if self.vertex or self.face or self.corner:
            mesh = mesh.with_attributes(vertex=self.vertex or None, face=self.face or None, corner=self.corner or None)
        return mesh


def _warn_left_out(name: str, why: str, what: str, stacklevel: int = 3) -> None:
    warnings.warn(f"{name}: {why}: left out {what} (.npz keeps everything)", GeometryWarning, stacklevel=stacklevel)


# ------------------------------------------------------------------ OBJ


def _obj_data(name: str, extras: dict) -> _Data:
    """The attributes of an OBJ file from ``_read_obj``'s extras: corner
    ``"uv"`` and ``"normal"`` as (table, index) when every corner has a
    ``vt`` (``vn``) index, face ``"group"`` and ``"material"`` as string
    arrays."""
    d = _Data()
    for key, attr, what in (("texcoords", "uv", "vt"), ("normals", "normal", "vn")):
        if key not in extras:
            continue
        index = extras["corner_" + key]
        if (index < 0).any():
            # some faces have no vt (or vn): a file's faces without a texture, as
            # Blender writes them; there is no value to give their corners
            continue
        d.corner[attr] = (extras[key], index)
    for key, attr in (("groups", "group"), ("materials", "material")):
        if "face_" + key in extras:
            names = extras[key[:-1] + "_names"]
            d.face[attr] = np.array(names, dtype=str)[extras["face_" + key]] if names else np.zeros(0, dtype=str)
    return d


def _obj_fields(name: str, mesh: Mesh):
    """What OBJ writes of ``mesh``'s data: corner ``"uv"`` (k 1 to 3) and
    ``"normal"`` (k 3), face ``"group"`` and ``"material"`` (1-D strings);
    the rest is left out with a GeometryWarning."""
    d = _Data.of(mesh)
    uv = d.corner.pop("uv", None)
    if uv is not None and not (uv.ndim == 1 or uv.shape[1] <= 3):
        d.corner["uv"] = uv
        uv = None
    normal = d.corner.pop("normal", None)
    if normal is not None and not (normal.ndim == 2 and normal.shape[1] == 3):
        d.corner["normal"] = normal
        normal = None
    labels = []
    for key in ("group", "material"):
        a = d.face.pop(key, None)
        if a is not None and not (a.ndim == 1 and a.dtype.kind in "US"):
            d.face[key] = a
            a = None
        labels.append(a)
    if d:
        _warn_left_out(name, "OBJ stores corner 'uv' and 'normal' and string face 'group' and 'material' only", d.names(), 4)
    return (uv, normal, *labels)


def _write_obj(tmp: str, mesh: Mesh, uv, normal, group, material) -> None:
    """OBJ through the core writer (``_core._write_obj``): ``vt``/``vn``
    tables of the distinct per-corner values (corners that share a value
    share a row, so a seam stays a seam), ``f v/vt/vn`` corners, and a ``g``
    or ``usemtl`` line wherever the face's group or material changes."""
    from topomesh._core import _write_obj as write

    def names(a):
        if a is None:
            return None
        ids = np.unique(a, return_inverse=True)
        return ids[1].reshape(-1).astype(np.int64), [str(x) for x in ids[0]]

    rows = lambda a: None if a is None else np.ascontiguousarray(a.reshape(len(a), -1), dtype=np.float64)  # noqa: E731
    write(mesh, tmp, rows(uv), rows(normal), names(group), names(material))


# ------------------------------------------------------------------ PLY

#: NumPy dtype -> PLY scalar type
_PLY_TYPE = {"i1": "char", "u1": "uchar", "i2": "short", "u2": "ushort", "i4": "int", "u4": "uint",
             "f4": "float", "f8": "double", "b1": "uchar", "f2": "float"}
_META = "topomesh-attribute"
_SAFE = re.compile(r"[!-~]+")  # printable ASCII without spaces: a PLY property name
_RESERVED = {"x", "y", "z", "sharpness", "vertex_indices", "corner_twins", "corner_sharpness"}


def _vertex_names(name: str, k: int | None) -> list[str]:
    if name in ("color", "colour") and k in (3, 4):
        return ["red", "green", "blue", "alpha"][:k]
    if name in ("normal", "normals") and k == 3:
        return ["nx", "ny", "nz"]
    return [name] if k is None else [f"{name}_{j}" for j in range(k)]


def _ply_fields(name: str | None, mesh: Mesh):
    """The extra PLY properties of ``mesh``'s data: ``(vertex, face, corner,
    comments)`` with ``vertex`` a list of (property, float64 column),
    ``face`` of (property, PLY type, column), ``corner`` of (property, (C, k)
    float64 rows written k per corner in one list), and the header comments
    that say which properties make which attribute. Strings, objects and
    names that cannot be PLY property names are left out with a
    GeometryWarning (none when ``name`` is None)."""
    d = _Data.of(mesh)
    used = set(_RESERVED)
    skipped = []
    vertex, face, corner, comments = [], [], [], []

    def claim(kind: str, attr: str, props: list[str]) -> bool:
        if not _SAFE.fullmatch(attr) or any(p in used for p in props):
            skipped.append(f"{kind} attribute {attr!r} (its name is no PLY property name or is taken)")
            return False
        used.update(props)
        return True

    for attr, a in d.vertex.items():
        k = None if a.ndim == 1 else a.shape[1]
        props = _vertex_names(attr, k)
        if claim("vertex", attr, props):
            cols = a.reshape(len(a), -1)
            vertex += [(p, cols[:, j]) for j, p in enumerate(props)]
            comments.append(f"{_META} vertex {attr} float64 {'-' if k is None else k} {' '.join(props)}")
    for attr, a in d.face.items():
        dt = a.dtype
        code = dt.str[1:]
        if dt.kind in "iu" and dt.itemsize == 8:
            lo, hi = (int(a.min()), int(a.max())) if a.size else (0, 0)
            if dt.kind == "u" and hi < 2**32:
                code = "u4"
            elif -(2**31) <= lo and hi < 2**31:
                code = "i4"
            elif -(2**53) <= lo and hi <= 2**53:
                code = "f8"
        if code not in _PLY_TYPE:
            skipped.append(f"face attribute {attr!r} (dtype {dt}: PLY holds numbers only)")
            continue
        tail = a.shape[1:]
        k = int(np.prod(tail)) if tail else None
        props = [attr] if k is None else [f"{attr}_{j}" for j in range(k)]
        if claim("face", attr, props):
            cols = a.reshape(len(a), -1).astype(np.dtype(code).newbyteorder("<"))
            face += [(p, _PLY_TYPE[code], cols[:, j]) for j, p in enumerate(props)]
            shape = "-" if k is None else "x".join(str(t) for t in tail)
            comments.append(f"{_META} face {attr} {dt.str} {shape} {' '.join(props)}")
    for attr, a in d.corner.items():
        k = None if a.ndim == 1 else a.shape[1]
        prop = "texcoord" if attr == "uv" and k == 2 else attr  # MeshLab's name for per-corner UVs
        if claim("corner", attr, [prop]):
            corner.append((prop, a.reshape(len(a), -1)))
            comments.append(f"{_META} corner {attr} float64 {'-' if k is None else k} {prop}")
    if d.corner_sharpness is not None:
        vertex.append(("sharpness", d.vertex_sharpness))
        corner.append(("corner_sharpness", d.corner_sharpness.reshape(-1, 1)))
        comments.append("topomesh-creases vertex sharpness, corner_sharpness: the sharpness of the edge leaving each corner")
    if skipped and name is not None:
        _warn_left_out(name, "PLY cannot store them", "; ".join(skipped), 4)
    return vertex, face, corner, comments


def _ply_data(name: str, vprops: dict, fprops: dict, lists: set, comments: list, n_corners: int) -> _Data:
    """Attributes and creases from PLY properties (``vprops``: vertex
    property -> column; ``fprops``: face property -> per-face column, or the
    concatenated values of a list property) and header comments. A file
    topomesh wrote says in its comments which properties make which
    attribute; in other files, vertex ``red green blue [alpha]`` become
    ``"color"``, ``nx ny nz`` ``"normal"``, other numeric vertex and face
    properties attributes of their name, a ``texcoord`` list of two
    values per corner the corner attribute ``"uv"`` and other lists of one
    number per corner corner attributes of their name (``lists`` names the
    list properties)."""
    d = _Data()
    metas = [c.split()[1:] for c in comments if c.split()[:1] == [_META]]
    if metas:
        for m in metas:
            if len(m) < 5 or m[0] not in ("vertex", "face", "corner"):
                raise MeshError(f"malformed comment {' '.join([_META] + m)!r}")
            kind, attr, dtype, shape, props = m[0], m[1], m[2], m[3], m[4:]
            src = vprops if kind == "vertex" else fprops
            if any(p not in src for p in props):
                continue  # the properties were removed by another program
            cols = [np.asarray(src[p]) for p in props]
            if kind == "corner":
                a = cols[0].reshape(n_corners, -1)
                a = a[:, 0] if shape == "-" else a
            else:
                a = np.column_stack(cols) if len(cols) > 1 or shape != "-" else cols[0]
                if shape not in ("-",):
                    a = a.reshape((len(a),) + tuple(int(t) for t in shape.split("x")))
            {"vertex": d.vertex, "face": d.face, "corner": d.corner}[kind][attr] = a.astype(np.dtype(dtype))
    else:
        rest = [p for p in vprops if p not in ("x", "y", "z", "sharpness")]
        for attr, props in (("color", ["red", "green", "blue", "alpha"]), ("normal", ["nx", "ny", "nz"])):
            have = [p for p in props if p in vprops]
            if len(have) >= 3 and have == props[: len(have)]:
                d.vertex[attr] = np.column_stack([np.asarray(vprops[p], dtype=np.float64) for p in have])
                rest = [p for p in rest if p not in have]
        for p in rest:
            d.vertex[p] = np.asarray(vprops[p], dtype=np.float64)
        for p, a in fprops.items():
            if p in ("vertex_indices", "vertex_index", "corner_twins", "corner_sharpness"):
                continue
            a = np.asarray(a)
            if p in ("texcoord", "texcoords") and len(a) == 2 * n_corners:
                d.corner["uv"] = a.reshape(-1, 2).astype(np.float64)
            elif a.dtype.kind not in "iufb":
                continue
            elif p not in lists:
                d.face[p] = a
            elif len(a) == n_corners:
                d.corner[p] = a.astype(np.float64)
    if "sharpness" in vprops or "corner_sharpness" in fprops:
        if "corner_sharpness" in fprops and len(fprops["corner_sharpness"]) == n_corners:
            d.corner_sharpness = np.asarray(fprops["corner_sharpness"], dtype=np.float64)
        if "sharpness" in vprops:
            d.vertex_sharpness = np.asarray(vprops["sharpness"], dtype=np.float64)
    return d


# ------------------------------------------------------------------ NPZ


def _npz_arrays(name: str | None, mesh: Mesh) -> dict:
    """The optional ``.npz`` entries of ``mesh``'s data: ``vertex_attr__<name>``,
    ``face_attr__<name>``, ``corner_attr__<name>``, ``corner_sharpness`` and
    ``vertex_sharpness``. Object arrays (which need pickle) are left out with
    a GeometryWarning."""
    d = _Data.of(mesh)
    out, skipped = {}, []
    for kind, attrs in (("vertex", d.vertex), ("face", d.face), ("corner", d.corner)):
        for attr, a in attrs.items():
            if a.dtype.kind == "O":
                skipped.append(f"{kind} attribute {attr!r} (object dtype: .npz is read without pickle)")
            else:
                out[f"{kind}_attr__{attr}"] = a
    if d.corner_sharpness is not None:
        out["corner_sharpness"], out["vertex_sharpness"] = d.corner_sharpness, d.vertex_sharpness
    if skipped and name is not None:
        _warn_left_out(name, ".npz cannot store them", "; ".join(skipped), 4)
    return out


def _npz_data(z: Any) -> _Data:
    d = _Data()
    for key in z.files:
        kind, sep, attr = key.partition("_attr__")
        if sep and kind in ("vertex", "face", "corner"):
            getattr(d, kind)[attr] = z[key]
    if "corner_sharpness" in z.files:
        d.corner_sharpness = z["corner_sharpness"]
        d.vertex_sharpness = z["vertex_sharpness"] if "vertex_sharpness" in z.files else None
    return d
