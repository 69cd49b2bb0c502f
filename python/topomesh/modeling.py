"""Example models of the high-genus dissertation's modeling tools — curved
handles (ch. IV) and rinds (ch. V) — and the simple bodies they start from.

Used by the tests, the notebook ``01_handles_and_rinds`` and the gallery::

    from topomesh.modeling import cup
    m = cup()          # genus 1, one component
"""

from __future__ import annotations

import itertools
from typing import Sequence

import numpy as np

from topomesh._core import Mesh


# ------------------------------------------------------------------ bodies


def grid_cube(n: int) -> Mesh:
    """The cube [-1, 1]³ with each side cut into ``n`` × ``n`` quads
    (V = 6n² + 2, F = 6n²)."""
    if n < 1:
        raise ValueError(f"grid_cube: n = {n} must be at least 1")
    index: dict[tuple[int, ...], int] = {}
    pts: list[list[float]] = []

    def vid(p: tuple[int, ...]) -> int:
        if p not in index:
            index[p] = len(pts)
            pts.append([c * 2.0 / n - 1.0 for c in p])
        return index[p]

    faces = []
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, n):
            for i, j in itertools.product(range(n), range(n)):
                quad = []
                for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    p = [0, 0, 0]
                    p[axis], p[u], p[v] = side, i + di, j + dj
                    quad.append(vid(tuple(p)))
                faces.append(quad if side == n else quad[::-1])
    return Mesh.from_polygons(np.array(pts), faces)


def cube_sphere(n: int) -> Mesh:
    """:func:`grid_cube` with its vertices pushed onto the unit sphere."""
    g = grid_cube(n)
    v = g.vertices
    return g.with_vertices(v / np.linalg.norm(v, axis=1, keepdims=True))


def prism(sides: int = 8, rings: int = 4, radius: float = 1.0, height: float = 2.0) -> Mesh:
    """A closed prism around the z axis from z = 0 to ``height``: faces
    ``ring * sides + i`` are the side quads (ring 0 at the bottom, side i
    centred at angle (i + ½)·2π/sides), then the bottom and top polygons."""
    a = np.arange(sides) * 2 * np.pi / sides
    pts = [(radius * np.cos(t), radius * np.sin(t), height * r / rings) for r in range(rings + 1) for t in a]
    faces = [
        [r * sides + i, r * sides + (i + 1) % sides, (r + 1) * sides + (i + 1) % sides, (r + 1) * sides + i]
        for r in range(rings)
        for i in range(sides)
    ]
    faces.append(list(range(sides))[::-1])
    faces.append([rings * sides + i for i in range(sides)])
    return Mesh.from_polygons(np.array(pts), faces)


def face_at(m: Mesh, centroid: Sequence[float], tol: float = 1e-9) -> int:
    """The face whose centroid is ``centroid``."""
    d = np.linalg.norm(m.face_centroids - np.asarray(centroid, float), axis=1)
    f = int(np.argmin(d))
    if d[f] > tol:
        raise ValueError(f"no face has its centroid at {tuple(centroid)}")
    return f


def edge_between(m: Mesh, a: int, b: int) -> int:
    """The one edge joining vertices ``a`` and ``b``."""
    e = m.edges
    hit = np.nonzero(((e[:, 0] == a) & (e[:, 1] == b)) | ((e[:, 0] == b) & (e[:, 1] == a)))[0]
    if len(hit) != 1:
        raise ValueError(f"{len(hit)} edges join vertices {a} and {b}")
    return int(hit[0])


# ----------------------------------------------------------------- models


def arch_cube(arches: int = 1, twist: int = 0) -> Mesh:
    """A 5 × 5 grid cube with ``arches`` (1 to 3) parallel curved handles over
    its top, each of 8 segments: genus = ``arches``. ``twist`` shifts the
    second corner of each handle by that many positions from the least-twist
    choice (a quarter turn each)."""
    m = grid_cube(5)
    for y in (0.0, -0.8, 0.8)[:arches]:
        a, b = face_at(m, [-0.8, y, 1]), face_at(m, [0.8, y, 1])
        if twist:
            # find the least-twist corner, then offset it
            base = m.add_handle(a, b, segments=8, weights=(3.0, 3.0))
            j0 = next(j for j in range(4) if np.allclose(
                m.add_handle(a, b, segments=8, weights=(3.0, 3.0), corners=(0, j)).vertices, base.vertices))
            m = m.add_handle(a, b, segments=8, weights=(3.0, 3.0), corners=(0, (j0 + twist) % 4))
        else:
            m = m.add_handle(a, b, segments=8, weights=(3.0, 3.0))
    return m


def triangle_hexagon_handle() -> Mesh:
    """A 5 × 5 grid cube whose top carries a triangle (half a quad, split
    with InsertEdge) and a hexagon (a quad with two sides subdivided), joined
    by a curved handle; the triangle is subdivided to six corners first."""
    m = grid_cube(5)
    fa = face_at(m, [-0.8, 0, 1])
    m, _ = m.insert_edge(fa, 0, fa, 2)
    fb = face_at(m, [0.8, 0, 1])
    off = np.concatenate([[0], np.cumsum(m.face_sizes)])
    q = m.face_indices[off[fb]:off[fb + 1]]
    for u, v in ((q[0], q[1]), (q[2], q[3])):
        m, _ = m.subdivide_edge(edge_between(m, int(u), int(v)))
    tri = int(np.nonzero(m.face_sizes == 3)[0][0])
    hexa = int(np.nonzero(m.face_sizes == 6)[0][0])
    return m.add_handle(tri, hexa, segments=8, weights=(3.0, 3.0))


def cup(sides: int = 12, thickness: float = 0.12) -> Mesh:
    """The dissertation's cup (its Fig. 65): the rind of a ``sides``-sided
    prism with its top punched, and a curved handle from the 4th to the 2nd
    ring of side quads facing +x. Genus 1."""
    body = prism(sides=sides, rings=5, radius=1.0, height=2.5)
    r = body.rind(thickness).punch(face_at(body, [0, 0, 2.5]))
    c = body.face_centroids
    upper = max(range(3 * sides, 4 * sides), key=lambda f: c[f][0])
    lower = max(range(1 * sides, 2 * sides), key=lambda f: c[f][0])
    pa, pb = r.face_pair(upper), r.face_pair(lower)
    assert pa is not None and pb is not None
    return r.mesh.add_handle(pa[0], pb[0], segments=10, weights=(1.6, 1.6))


def peeled_rind_sphere(n: int = 6, thickness: float = 0.12) -> Mesh:
    """A rind of :func:`cube_sphere` with a 2 × 2 window peeled on each of its
    six sides (``n`` even): six holes, genus 5."""
    g = grid_cube(n)
    c = g.face_centroids
    window = [f for f in range(g.n_faces) if np.sort(np.abs(c[f]))[1] < 1.01 * 2 / n]
    return cube_sphere(n).rind(thickness).peel(window).mesh
