"""Compare a topomesh result with OpenSubdiv's up to the order of vertices, faces and corners.

OpenSubdiv (through Blender) numbers the refined vertices its own way and hands them back in
float32, so points are matched by position: :func:`match_points` pairs each of ours with its
nearest reference point (scipy's cKDTree, both ways, so the pairing is a bijection) within
``rtol`` times the bounding-box diagonal. Faces are then matched by their sets of matched
vertices, and a corner (face, vertex) by its face and vertex; that identifies corners of any
mesh whose faces have distinct vertex sets, which every reference fixture has.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from tests.osd.reference import flatten_faces

RTOL = 1e-6  # float32 reference: ~6e-8 relative per coordinate, with margin for a few levels


def _scale(a: np.ndarray, b: np.ndarray) -> float:
    pts = np.vstack([a, b])
    return float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0))) or 1.0


def match_points(ours: Any, ref: Any, rtol: float = RTOL) -> np.ndarray:
    """Index into ``ref`` of each point of ``ours``; AssertionError naming the worst point if the
    two sets differ in size, or are not equal up to order within ``rtol`` x bbox diagonal."""
    a = np.asarray(ours, dtype=np.float64)
    b = np.asarray(ref, dtype=np.float64)
    if a.shape != b.shape:
        raise AssertionError(f"point counts differ: ours {a.shape}, reference {b.shape}")
    tol = rtol * _scale(a, b)
    d_ab, i_ab = cKDTree(b).query(a)
    d_ba, i_ba = cKDTree(a).query(b)
    worst = int(np.argmax(d_ab))
    if d_ab[worst] > tol:
        raise AssertionError(
            f"our point {worst} {a[worst].tolist()} is {d_ab[worst]:.3g} from the nearest reference "
            f"point {b[i_ab[worst]].tolist()} (tolerance {tol:.3g})")
    worst = int(np.argmax(d_ba))
    if d_ba[worst] > tol:
        raise AssertionError(
            f"reference point {worst} {b[worst].tolist()} is {d_ba[worst]:.3g} from our nearest "
            f"(tolerance {tol:.3g})")
    if len(np.unique(i_ab)) != len(a):
        raise AssertionError("two of our points match the same reference point (coincident points?)")
    return i_ab


def same_points(a: Any, b: Any, rtol: float = RTOL) -> bool:
    """True when ``a`` and ``b`` are the same point sets up to order (see :func:`match_points`)."""
    try:
        match_points(a, b, rtol)
    except AssertionError:
        return False
    return True


def match_faces(ours_faces: Any, ref_faces: Any, vertex_map: np.ndarray) -> np.ndarray:
    """Index into the reference faces of each of our faces, by matched vertex sets."""
    sizes, idx = flatten_faces(ours_faces)
    rsizes, ridx = flatten_faces(ref_faces)
    if len(sizes) != len(rsizes):
        raise AssertionError(f"face counts differ: ours {len(sizes)}, reference {len(rsizes)}")
    rstarts = np.concatenate([[0], np.cumsum(rsizes)[:-1]])
    key = {}
    for f, (s, n) in enumerate(zip(rstarts, rsizes)):
        k = tuple(sorted(ridx[s : s + n].tolist()))
        if k in key:
            raise AssertionError(f"reference faces {key[k]} and {f} have the same vertices")
        key[k] = f
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    out = np.empty(len(sizes), dtype=np.int64)
    for f, (s, n) in enumerate(zip(starts, sizes)):
        k = tuple(sorted(vertex_map[idx[s : s + n]].tolist()))
        if k not in key:
            raise AssertionError(f"our face {f} (vertices {idx[s:s+n].tolist()}) has no reference face")
        out[f] = key[k]
    return out


def match_corners(ours_positions: Any, ours_faces: Any, ref: Any, rtol: float = RTOL) -> np.ndarray:
    """Index into ``ref``'s corners (``ref.face_indices`` / ``ref.uvs`` order) of each of our
    corners (the flattened ``ours_faces``), matching vertices by position and faces by vertex set."""
    vmap = match_points(ours_positions, ref.positions, rtol)
    fmap = match_faces(ours_faces, (ref.face_sizes, ref.face_indices), vmap)
    sizes, idx = flatten_faces(ours_faces)
    rstarts = np.concatenate([[0], np.cumsum(ref.face_sizes)[:-1]])
    out = np.empty(len(idx), dtype=np.int64)
    c = 0
    for f, n in enumerate(sizes):
        rs, rn = rstarts[fmap[f]], ref.face_sizes[fmap[f]]
        rverts = ref.face_indices[rs : rs + rn].tolist()
        for v in idx[c : c + n]:
            out[c] = rs + rverts.index(int(vmap[v]))
            c += 1
    return out


def assert_same_mesh(ours_positions: Any, ours_faces: Any, ref: Any, ours_uvs: Any = None, rtol: float = RTOL,
                     uv_atol: float = 1e-6) -> None:
    """Our refined mesh equals OpenSubdiv's ``ref`` (a :class:`tests.osd.reference.Refined`) up to
    the order of vertices, faces and corners: the same points (``rtol`` x bbox diagonal), the
    same faces on them, and, when ``ours_uvs`` (C, 2) is given, the same UV at every corner
    (``uv_atol``: UVs live in [0, 1], the reference's are float32)."""
    cmap = match_corners(ours_positions, ours_faces, ref, rtol)
    if ours_uvs is not None:
        if ref.uvs is None:
            raise AssertionError("the reference has no UVs: pass uvs= to refine()")
        uv = np.asarray(ours_uvs, dtype=np.float64)
        err = np.abs(uv - ref.uvs[cmap]).max(axis=1)
        worst = int(np.argmax(err))
        if err[worst] > uv_atol:
            raise AssertionError(f"our corner {worst} has UV {uv[worst].tolist()}, the reference "
                                 f"{ref.uvs[cmap[worst]].tolist()} (atol {uv_atol})")
