"""The published Catmull-Clark rules, evaluated on one level of a polygon mesh, to check that the
reference (and the harness's option mapping) does what OpenSubdiv documents.

Catmull & Clark 1978 for the smooth rules; DeRose, Kass & Truong 1998 (and OpenSubdiv's Sdc
"Catmark" scheme with the uniform crease method) for sharp and semi-sharp edges: an edge of
sharpness s >= 1 gets its midpoint, 0 < s < 1 blends the smooth point towards the midpoint by s,
and the child edges get s - 1.
"""

from __future__ import annotations

from collections import defaultdict
from typing import Any

import numpy as np

from tests.osd.reference import flatten_faces


def face_lists(faces: Any) -> list[list[int]]:
    sizes, idx = flatten_faces(faces)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(int)
    return [idx[s : s + n].tolist() for s, n in zip(starts, sizes)]


def edge_faces(faces: Any) -> dict[tuple[int, int], list[int]]:
    """Faces on each undirected edge ``(min, max)``."""
    out: dict[tuple[int, int], list[int]] = defaultdict(list)
    for f, fv in enumerate(face_lists(faces)):
        for a, b in zip(fv, fv[1:] + fv[:1]):
            out[(min(a, b), max(a, b))].append(f)
    return dict(out)


def centroids(positions: np.ndarray, faces: Any) -> np.ndarray:
    return np.array([positions[fv].mean(axis=0) for fv in face_lists(faces)])


def edge_point(positions: np.ndarray, faces: Any, a: int, b: int, sharpness: float = 0.0) -> np.ndarray:
    """Catmull-Clark edge point of interior edge (a, b) with the given sharpness (boundary edges:
    pass ``inf``, they are infinitely sharp)."""
    mid = (positions[a] + positions[b]) / 2
    if sharpness >= 1:
        return mid
    fs = edge_faces(faces)[(min(a, b), max(a, b))]
    c = centroids(positions, faces)[fs]
    smooth = (positions[a] + positions[b] + c.sum(axis=0)) / 4
    return (1 - sharpness) * smooth + sharpness * mid if sharpness > 0 else smooth


def neighbours(faces: Any, v: int) -> list[int]:
    return sorted({b for a, b in edge_faces(faces) if a == v} | {a for a, b in edge_faces(faces) if b == v})


def smooth_vertex_point(positions: np.ndarray, faces: Any, v: int) -> np.ndarray:
    """Catmull-Clark vertex point of an interior vertex: (Q + 2 R + (n - 3) v) / n."""
    fl = face_lists(faces)
    q = np.mean([positions[fv].mean(axis=0) for fv in fl if v in fv], axis=0)
    nb = neighbours(faces, v)
    r = np.mean([(positions[v] + positions[u]) / 2 for u in nb], axis=0)
    n = len(nb)
    return (q + 2 * r + (n - 3) * positions[v]) / n


def crease_vertex_point(positions: np.ndarray, a: int, v: int, b: int) -> np.ndarray:
    """Vertex point on a crease or boundary curve through a, v, b: (a + 6 v + b) / 8."""
    return (positions[a] + 6 * positions[v] + positions[b]) / 8


def boundary_edges(faces: Any) -> list[tuple[int, int]]:
    return [e for e, fs in edge_faces(faces).items() if len(fs) == 1]


def nearest(points: np.ndarray, p: np.ndarray) -> tuple[int, float]:
    """Index of the point of ``points`` nearest to ``p``, and its distance."""
    d = np.linalg.norm(np.asarray(points) - p, axis=1)
    i = int(np.argmin(d))
    return i, float(d[i])


def scale(points: np.ndarray) -> float:
    return float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))


# Loop (Loop 1987; OpenSubdiv's Sdc "Loop" scheme: Loop's original beta, the same sharp rules)


def opposite_vertices(faces: Any, a: int, b: int) -> list[int]:
    """The third vertex of each triangle on edge (a, b)."""
    fl = face_lists(faces)
    return [next(w for w in fl[f] if w not in (a, b)) for f in edge_faces(faces)[(min(a, b), max(a, b))]]


def loop_edge_point(positions: np.ndarray, faces: Any, a: int, b: int, sharpness: float = 0.0) -> np.ndarray:
    """Loop edge point of interior edge (a, b): 3/8 (a + b) + 1/8 (c + d), blended towards the
    midpoint by the sharpness as in Catmull-Clark."""
    mid = (positions[a] + positions[b]) / 2
    if sharpness >= 1:
        return mid
    c, d = opposite_vertices(faces, a, b)
    smooth = 3 / 8 * (positions[a] + positions[b]) + 1 / 8 * (positions[c] + positions[d])
    return (1 - sharpness) * smooth + sharpness * mid if sharpness > 0 else smooth


def loop_vertex_point(positions: np.ndarray, faces: Any, v: int) -> np.ndarray:
    """Loop vertex point of an interior vertex: (1 - n beta) v + beta sum(neighbours), with
    Loop's beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n."""
    nb = neighbours(faces, v)
    n = len(nb)
    beta = (5 / 8 - (3 / 8 + np.cos(2 * np.pi / n) / 4) ** 2) / n
    return (1 - n * beta) * positions[v] + beta * positions[nb].sum(axis=0)
