"""Open meshes shared by the tests: surfaces with boundary loops, as users
bring them (a scanned patch, a tube without caps, a terrain grid).

Each builder returns ``(vertices, faces)``: float64 ``(n, 3)`` positions and a
list of faces (lists of vertex indices, counter-clockwise seen from the side
the surface's normal points to, consistently oriented). :func:`mesh` builds
the topomesh :class:`~topomesh.Mesh` (kept open, one hole face per boundary
loop); :data:`EXPECTED` gives what every builder's default call must have:
χ = V − E + F of the open surface, the number of boundary loops and the genus
(χ = 2 − 2g − b, all of them connected). The geometry is rendered-looking:
no coincident points, no zero-area faces, faces planar or nearly so.

    >>> from tests.open_meshes import mesh, EXPECTED
    >>> m = mesh("annulus")
    >>> (m.euler_characteristic, m.n_boundary_loops) == EXPECTED["annulus"][:2]
    True
"""

from __future__ import annotations

from typing import Callable

import numpy as np

import topomesh

Faces = list[list[int]]


def _ccw_in_xy(vertices: np.ndarray, faces: Faces) -> Faces:
    """Faces of a patch that projects one-to-one onto the xy plane, each
    turned counter-clockwise seen from +z (normals up)."""
    out = []
    for f in faces:
        p = vertices[f][:, :2]
        area = np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
        out.append(list(f) if area > 0 else list(f[::-1]))
    return out


def _dome(xy: np.ndarray, height: float = 0.25) -> np.ndarray:
    """Lift planar points onto a gentle dome, so the patch is not flat."""
    r2 = (xy**2).sum(axis=1)
    return np.column_stack([xy, height * np.exp(-r2 / 2.0)])


def disk(n: int = 8) -> tuple[np.ndarray, Faces]:
    """A domed disk: a fan of ``n`` triangles around a centre, then a ring of
    ``n`` quads. One boundary loop (the outer rim, ``n`` edges), χ = 1.
    V = 2n + 1, E = 4n, F = 2n."""
    t = 2 * np.pi * np.arange(n) / n
    ring = lambda r: np.column_stack([r * np.cos(t), r * np.sin(t)])  # noqa: E731
    xy = np.vstack([[[0.0, 0.0]], ring(1.0), ring(2.0)])
    v = _dome(xy)
    inner = lambda i: 1 + i % n  # noqa: E731
    outer = lambda i: 1 + n + i % n  # noqa: E731
    faces = [[0, inner(i), inner(i + 1)] for i in range(n)]
    faces += [[inner(i), outer(i), outer(i + 1), inner(i + 1)] for i in range(n)]
    return v, _ccw_in_xy(v, faces)


def annulus(n: int = 12, rows: int = 2) -> tuple[np.ndarray, Faces]:
    """A flat ring of quads between radii 1 and 2: ``n`` around, ``rows``
    across. Two boundary loops (inner and outer rim, ``n`` edges each), χ = 0.
    V = n(rows + 1), E = n(2 rows + 1), F = n·rows."""
    t = 2 * np.pi * np.arange(n) / n
    radii = np.linspace(1.0, 2.0, rows + 1)
    xy = np.vstack([np.column_stack([r * np.cos(t), r * np.sin(t)]) for r in radii])
    v = np.column_stack([xy, np.zeros(len(xy))])
    at = lambda k, i: k * n + i % n  # noqa: E731
    faces = [[at(k, i), at(k, i + 1), at(k + 1, i + 1), at(k + 1, i)] for k in range(rows) for i in range(n)]
    return v, _ccw_in_xy(v, faces)


def cylinder(n: int = 12, rows: int = 4, radius: float = 1.0, height: float = 2.0) -> tuple[np.ndarray, Faces]:
    """An open tube of quads around the z axis (no caps), normals outward:
    ``n`` around, ``rows`` along. Two boundary loops (the rims), χ = 0.
    V = n(rows + 1), E = n(2 rows + 1), F = n·rows."""
    t = 2 * np.pi * np.arange(n) / n
    z = np.linspace(0.0, height, rows + 1)
    v = np.vstack([np.column_stack([radius * np.cos(t), radius * np.sin(t), np.full(n, zk)]) for zk in z])
    at = lambda k, i: k * n + i % n  # noqa: E731
    faces = [[at(k, i), at(k, i + 1), at(k + 1, i + 1), at(k + 1, i)] for k in range(rows) for i in range(n)]
    return v, faces


def quad_grid(n: int = 4, size: float = 1.0) -> tuple[np.ndarray, Faces]:
    """An open, flat ``n`` × ``n`` grid of square quads on [0, size]² in the
    plane z = 0, normals +z; vertex ``j (n + 1) + i`` is at ``(i, j)·size/n``.
    One boundary loop (4n edges), χ = 1. V = (n + 1)², E = 2n(n + 1), F = n²."""
    s = np.linspace(0.0, size, n + 1)
    x, y = np.meshgrid(s, s)
    v = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    at = lambda i, j: j * (n + 1) + i  # noqa: E731
    faces = [[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)] for j in range(n) for i in range(n)]
    return v, faces


def mixed() -> tuple[np.ndarray, Faces]:
    """An open domed patch of three face sizes: a hexagon, a quad on each of
    its sides and a triangle between neighbouring quads. One boundary loop
    (12 edges), χ = 1. V = 18, E = 30, F = 13 (1 hexagon, 6 quads, 6 triangles)."""
    t = 2 * np.pi * np.arange(6) / 6
    a = np.column_stack([np.cos(t), np.sin(t)])
    pts = [a]
    p, q = [], []
    for i in range(6):
        j = (i + 1) % 6
        mid = 0.5 * (a[i] + a[j])
        out = mid / np.linalg.norm(mid)
        p.append(a[i] + out)  # outside a_i, across the quad on side (i, i + 1)
        q.append(a[j] + out)  # outside a_{i+1}
    pts += [np.array(p), np.array(q)]
    v = _dome(np.vstack(pts))
    A = lambda i: i % 6  # noqa: E731
    P = lambda i: 6 + i % 6  # noqa: E731
    Q = lambda i: 12 + i % 6  # noqa: E731
    faces = [list(range(6))]
    faces += [[A(i), P(i), Q(i), A(i + 1)] for i in range(6)]
    faces += [[A(i + 1), Q(i), P(i + 1)] for i in range(6)]
    return v, _ccw_in_xy(v, faces)


def genus2_three_holes() -> tuple[np.ndarray, Faces]:
    """A closed genus-2 slab (``topomesh.genus_surface(2)``: 48 vertices, 50
    quads, normals outward) with three quads removed, no two of them sharing
    a vertex: a genus-2 surface with three boundary loops of 4 edges each,
    χ = 2 − 2·2 − 3 = −5. V = 48, E = 100, F = 47."""
    g = topomesh.genus_surface(2)
    v = np.array(g.vertices)
    faces = [list(map(int, f)) for f in np.split(g.face_indices, np.cumsum(g.face_sizes)[:-1])]
    removed: list[int] = []
    used: set[int] = set()
    # spread over the face list: top, bottom and tunnel-wall quads alike
    for k in range(0, len(faces), 7):
        if len(removed) == 3:
            break
        if used.isdisjoint(faces[k]):
            removed.append(k)
            used.update(faces[k])
    return v, [f for k, f in enumerate(faces) if k not in removed]


#: name -> builder (default arguments)
BUILDERS: dict[str, Callable[[], tuple[np.ndarray, Faces]]] = {
    "disk": disk,
    "annulus": annulus,
    "cylinder": cylinder,
    "genus2_three_holes": genus2_three_holes,
    "quad_grid": quad_grid,
    "mixed": mixed,
}

#: name -> (χ of the open surface, boundary loops, genus) of the default call
EXPECTED: dict[str, tuple[int, int, int]] = {
    "disk": (1, 1, 0),
    "annulus": (0, 2, 0),
    "cylinder": (0, 2, 0),
    "genus2_three_holes": (-5, 3, 2),
    "quad_grid": (1, 1, 0),
    "mixed": (1, 1, 0),
}

#: the four open inputs of issue 15's "done when" list
FOUR = ("disk", "annulus", "cylinder", "genus2_three_holes")


def mesh(name: str, *args, **kwargs) -> topomesh.Mesh:
    """The topomesh Mesh of builder ``name`` (called with ``args``/``kwargs``), kept open."""
    v, f = BUILDERS[name](*args, **kwargs)
    return topomesh.Mesh.from_polygons(v, f)


def trimesh_boundary_edges(tm) -> set[tuple[int, int]]:
    """Boundary edges as trimesh sees them: the (sorted) vertex pairs of
    ``tm.edges_sorted`` that occur once."""
    pairs, counts = np.unique(np.asarray(tm.edges_sorted), axis=0, return_counts=True)
    return {(int(a), int(b)) for a, b in pairs[counts == 1]}


def n_edge_loops(edges) -> int:
    """Connected pieces of a set of edges (the boundary loops when no two
    loops share a vertex)."""
    parent: dict[int, int] = {}

    def root(x: int) -> int:
        parent.setdefault(x, x)
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b in edges:
        parent[root(int(a))] = root(int(b))
    return len({root(x) for x in list(parent)})


def sorted_edges(edges) -> set[tuple[int, int]]:
    """Edges (k, 2) as a set of sorted vertex pairs."""
    return {(min(int(a), int(b)), max(int(a), int(b))) for a, b in edges}
