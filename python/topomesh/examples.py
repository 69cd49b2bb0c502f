"""Example inputs for the Sierpinski scheme, one per vertex class of the
Sierpinski paper (Srinivasan & Akleman, section 5).

The paper classifies a vertex by the pyramid its straight edges make (the
cone over its link polygon): *convex*, *star*, *concave*, *planar* and
*saddle*, and shows what each class does under the scheme (Figs. 8–10): star
vertices give star-shaped back faces, concave vertices inverted pyramids,
planar vertices flattened pyramids, saddle vertices self-intersecting ones.
The Platonic solids have convex vertices only; these builders give the other
four. In each, **vertex 0 is the vertex of the class named**, so tests and
notebooks can look at it; in terms that can be measured, with ``n`` the
outward vertex normal, ``δ`` the angle deficit (2π minus the face angles) and
``h_i = n·(p_i − p_0)`` the heights of the neighbours:

========  ====================================================================
convex    δ > 0, every ``h_i < 0``, the link projected along ``n`` is convex
star      δ > 0, every ``h_i < 0``, the projected link is non-convex (a star)
concave   δ > 0, every ``h_i > 0``: the tip points into the solid
planar    δ = 0, every ``h_i = 0``
saddle    δ < 0, the ``h_i`` change sign at least four times around the link
========  ====================================================================

Every builder gives a closed, consistently oriented manifold of genus 0 with
positive volume, built with :meth:`topomesh.Mesh.from_polygons`.
"""

from __future__ import annotations

import numpy as np

from topomesh import Mesh

__all__ = ["star_prism", "dented_cube", "planar_vertex_box", "monkey_saddle", "terrain", "uv_cube", "checker"]


def star_prism(points: int = 5, inner: float = 0.45, height: float = 0.6, apex: float = 0.5) -> Mesh:
    """A prism over an ``points``-pointed star, capped by a star pyramid.

    **Star vertex**: vertex 0, the apex of the cap, on the axis at
    ``height + apex``; its ``2·points`` edges run to the star's corners on the
    top rim, so its link is the star polygon (non-convex, star-shaped about the
    axis) and all of it lies below the apex. The bottom is **one non-convex
    face** (the flat ``2·points``-gon star); the sides are quads. The star's
    reflex corners on the top rim are **saddle** vertices (four neighbours,
    alternately above and below); on the bottom they are three-valent with
    negative angle deficit (one concave edge, the vertical one). The tips are
    convex.

    Parameters
    ----------
    points : int
        Number of star points (≥ 3).
    inner : float
        Radius of the reflex corners; the tips are at radius 1.
    height : float
        Height of the prism (bottom at z = 0).
    apex : float
        Height of the apex above the top rim.

    Returns
    -------
    Mesh
        With ``p = points``: V = 4p + 1, E = 8p, F = 4p + 1 (2p triangles,
        2p quads and the 2p-gon bottom).
    """
    if points < 3:
        raise ValueError("a star needs at least 3 points")
    n = 2 * points
    ang = np.pi / 2 + np.arange(n) * np.pi / points
    rad = np.where(np.arange(n) % 2 == 0, 1.0, inner)
    ring = np.column_stack([rad * np.cos(ang), rad * np.sin(ang)])
    top = np.column_stack([ring, np.full(n, height)])
    bot = np.column_stack([ring, np.zeros(n)])
    verts = np.vstack([[0.0, 0.0, height + apex], top, bot])
    t = lambda i: 1 + i % n  # noqa: E731
    b = lambda i: 1 + n + i % n  # noqa: E731
    faces = [[0, t(i), t(i + 1)] for i in range(n)]  # the star cap (counter-clockwise from above)
    faces += [[t(i + 1), t(i), b(i), b(i + 1)] for i in range(n)]  # the sides
    faces.append([b(i) for i in reversed(range(n))])  # the non-convex bottom, seen from below
    return Mesh.from_polygons(verts, faces)


def dented_cube(depth: float = 0.5) -> Mesh:
    """The cube ``[-1, 1]³`` with its top face pushed in at the centre.

    **Concave vertex**: vertex 0, the centre of the top face moved down to
    ``z = 1 − depth``; the top face is replaced by the four triangles from it
    to the top edges. Its four neighbours (the top corners) all lie *above* it,
    on the outer side: an inverted pyramid, angle deficit > 0. The other faces
    are the cube's five quads. The dent pulls the links of the four top corners
    in: they become **star** vertices (the paper's Fig. 9 input also has both
    star and concave vertices); the four bottom corners are convex.

    Parameters
    ----------
    depth : float
        How far the centre is pushed in, in (0, 2).
    """
    if not 0.0 < depth < 2.0:
        raise ValueError("depth must be in (0, 2)")
    c = [[x, y, z] for z in (-1.0, 1.0) for y in (-1.0, 1.0) for x in (-1.0, 1.0)]
    verts = np.array([[0.0, 0.0, 1.0 - depth]] + c)
    # corner (x, y, z) ↦ 1 + bits; top corners 5..8
    v = lambda x, y, z: 1 + (x > 0) + 2 * (y > 0) + 4 * (z > 0)  # noqa: E731
    lo, hi = -1, 1
    faces = [
        [v(lo, lo, lo), v(lo, hi, lo), v(hi, hi, lo), v(hi, lo, lo)],  # bottom
        [v(lo, lo, lo), v(hi, lo, lo), v(hi, lo, hi), v(lo, lo, hi)],  # front (y = -1)
        [v(hi, lo, lo), v(hi, hi, lo), v(hi, hi, hi), v(hi, lo, hi)],  # right (x = +1)
        [v(hi, hi, lo), v(lo, hi, lo), v(lo, hi, hi), v(hi, hi, hi)],  # back (y = +1)
        [v(lo, hi, lo), v(lo, lo, lo), v(lo, lo, hi), v(lo, hi, hi)],  # left (x = -1)
    ]
    rim = [v(lo, lo, hi), v(hi, lo, hi), v(hi, hi, hi), v(lo, hi, hi)]  # top, counter-clockwise from above
    faces += [[0, rim[i], rim[(i + 1) % 4]] for i in range(4)]
    return Mesh.from_polygons(verts, faces)


def planar_vertex_box(size: tuple[float, float, float] = (1.5, 1.0, 1.0), n: int = 2) -> Mesh:
    """A box whose every face is an ``n × n`` grid of quads.

    **Planar vertices**: the grid points inside the faces; all their neighbours
    and faces lie in the face's plane (angle deficit 0). Vertex 0 is the one
    nearest the centre of the top face (its centre for even ``n``). The grid
    points inside the box's edges have angle deficit 0 too but sit on a crease;
    the eight corners are convex. The paper's Fig. 10 shows what planar vertices
    do under the scheme: flattened pyramids, more with every iteration.

    Parameters
    ----------
    size : (float, float, float)
        Edge lengths; the box is centred at the origin.
    n : int
        Quads per face side (≥ 2, so that there is an inner grid point).
    """
    if n < 2:
        raise ValueError("n must be at least 2 for a face to have an inner vertex")
    half = np.asarray(size, dtype=float) / 2
    index: dict[tuple[int, int, int], int] = {}
    verts: list[np.ndarray] = []

    def vid(g: tuple[int, int, int]) -> int:
        if g not in index:
            index[g] = len(verts)
            verts.append(half * (np.array(g, dtype=float) * 2 / n - 1))
        return index[g]

    vid((n // 2, n // 2, n))  # vertex 0: centre of the top face
    faces = []
    for axis in range(3):
        u, w = (axis + 1) % 3, (axis + 2) % 3  # (u, w, axis) is right-handed
        for side in (0, n):
            for i in range(n):
                for j in range(n):
                    quad = []
                    for a, b in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                        g = [0, 0, 0]
                        g[axis], g[u], g[w] = side, a, b
                        quad.append(vid((g[0], g[1], g[2])))
                    faces.append(quad if side == n else quad[::-1])
    return Mesh.from_polygons(np.array(verts), faces)


def monkey_saddle(sides: int = 6, height: float = 1.0, amplitude: float = 0.35) -> Mesh:
    """A prism over a regular ``sides``-gon whose top is a monkey saddle.

    **Saddle vertex**: vertex 0, the centre of the top, joined by triangles to
    the rim, whose corners alternate between ``height ± amplitude``: its
    neighbours lie alternately above and below it (``sides`` sign changes;
    three up and three down for the default hexagon, a monkey saddle), angle
    deficit < 0. The paper: a saddle vertex gives a self-intersecting pyramid,
    one per saddle vertex, smaller with every iteration. The bottom is one flat
    ``sides``-gon, the walls are (non-planar) quads.

    Parameters
    ----------
    sides : int
        Even number of rim corners (≥ 4).
    height : float
        Mean height of the rim (bottom at z = 0).
    amplitude : float
        Rim corners alternate ``height + amplitude`` and ``height − amplitude``.
    """
    if sides < 4 or sides % 2:
        raise ValueError("sides must be even and at least 4")
    ang = np.arange(sides) * 2 * np.pi / sides
    z = height + amplitude * np.where(np.arange(sides) % 2 == 0, 1.0, -1.0)
    top = np.column_stack([np.cos(ang), np.sin(ang), z])
    bot = np.column_stack([np.cos(ang), np.sin(ang), np.zeros(sides)])
    verts = np.vstack([[0.0, 0.0, height], top, bot])
    t = lambda i: 1 + i % sides  # noqa: E731
    b = lambda i: 1 + sides + i % sides  # noqa: E731
    faces = [[0, t(i), t(i + 1)] for i in range(sides)]
    faces += [[t(i + 1), t(i), b(i), b(i + 1)] for i in range(sides)]
    faces.append([b(i) for i in reversed(range(sides))])
    return Mesh.from_polygons(verts, faces)


def terrain(n: int = 6) -> Mesh:
    """An open n × n quad patch of terrain over [0, 1]²: one boundary loop,
    four corners of valence 2 (where the boundary options differ).

    Returns
    -------
    Mesh
        Open (``n_boundary_loops == 1``), vertex ``0, n, n(n+1), (n+1)² − 1`` the corners.
    """
    i, j = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    v = np.c_[i.ravel(), j.ravel(), 0.25 * np.sin(3 * i.ravel()) * np.cos(2.5 * j.ravel())]
    w = n + 1
    faces = [[a, a + 1, a + w + 1, a + w] for a in (r * w + c for r in range(n) for c in range(n))]
    return Mesh.from_polygons(v, faces)


def uv_cube() -> Mesh:
    """The cube with UVs of a cross unfolding (14 distinct UVs in [0, 1]², seams where
    the cross was cut) as the corner attribute ``"uv"``."""
    from topomesh import cube

    c = cube()
    faces = c.face_indices.reshape(6, 4)
    cells = {(0, 0, -1): (1, 0), (0, 0, 1): (1, 2), (0, -1, 0): (1, 1), (0, 1, 0): (1, 3), (-1, 0, 0): (0, 1), (1, 0, 0): (2, 1)}
    uv = []
    for f, n in zip(faces, np.rint(c.face_normals).astype(int)):
        col, row = cells[(int(n[0]), int(n[1]), int(n[2]))]
        q = c.vertices[f]
        a, b = q[1] - q[0], q[3] - q[0]
        for p in q:
            d = p - q[0]
            uv.append([col + d @ a / (a @ a), row + d @ b / (b @ b)])
    return c.with_attributes(corner={"uv": np.array(uv) / [3, 4]})


def checker(mesh: Mesh, squares: int = 8, name: str = "uv") -> np.ndarray:
    """0/1 per face: the checkerboard square (``squares`` per unit of the
    cross's cells) that the face's mean corner UV falls in, for colouring."""
    u = mesh.corner_attributes[name]
    starts = np.r_[0, np.cumsum(mesh.face_sizes)[:-1]]
    mean = np.add.reduceat(u, starts) / mesh.face_sizes[:, None]
    return (np.floor(mean[:, 0] * squares * 3) + np.floor(mean[:, 1] * squares * 4)) % 2
