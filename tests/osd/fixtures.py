"""Reference meshes for the OpenSubdiv comparisons (issue 15, part 6): geometry a user would render.

Each fixture is a :class:`Fixture`: vertices, faces (lists of vertex indices, counter-clockwise
seen from outside), the OpenSubdiv options it is meant for (keywords of
``tests.osd.refine``), and what it exercises.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np


@dataclass(frozen=True)
class Fixture:
    name: str
    vertices: np.ndarray
    faces: list[list[int]]
    options: dict[str, Any] = field(default_factory=dict)
    about: str = ""
    #: indexed form of ``options["uvs"]`` (as in OBJ's vt / f v/vt): distinct UVs (U, 2) and the
    #: UV index of each corner (C,), so that ``uv_table[uv_index] == options["uvs"]``
    uv_table: np.ndarray | None = None
    uv_index: np.ndarray | None = None

    @property
    def corner_count(self) -> int:
        return sum(len(f) for f in self.faces)


def quad_grid(n: int = 4) -> Fixture:
    """An open n x n quad patch of terrain over [0, 1]^2, z = 0.15 sin(2.5 x) cos(2 y) + 0.1 x y:
    non-planar so the interior rules show, with boundary vertices of valence 3 and four corners
    of valence 2 (the boundary interpolation options differ exactly there)."""
    xs = np.linspace(0.0, 1.0, n + 1)
    v = np.array([[x, y, 0.15 * math.sin(2.5 * x) * math.cos(2.0 * y) + 0.1 * x * y] for y in xs for x in xs])
    faces = [[j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i]
             for j in range(n) for i in range(n)]
    return Fixture("quad_grid", v, faces, {}, "open 4x4 quad terrain patch: boundary curve rule, corners")


def grid_corners(n: int = 4) -> list[int]:
    """The four valence-2 corner vertices of :func:`quad_grid`."""
    return [0, n, n * (n + 1), (n + 1) ** 2 - 1]


def cylinder(around: int = 8, rings: int = 3, radius: float = 1.0, height: float = 2.0) -> Fixture:
    """An open tube without caps (``around`` x ``rings`` quads), slightly flared (radius grows
    with height) so the two boundary loops are not the same circle: two boundary loops, no
    corners, every boundary vertex of valence 3."""
    v = []
    for r in range(rings + 1):
        z = height * r / rings
        rad = radius * (1.0 + 0.15 * r / rings)
        v += [[rad * math.cos(2 * math.pi * k / around), rad * math.sin(2 * math.pi * k / around), z]
              for k in range(around)]
    faces = [[r * around + k, r * around + (k + 1) % around, (r + 1) * around + (k + 1) % around,
              (r + 1) * around + k] for r in range(rings) for k in range(around)]
    return Fixture("cylinder", np.array(v, dtype=np.float64), faces, {}, "open tube: two boundary loops")


# cube [-1, 1]^3, vertex index = (x > 0) + 2 (y > 0) + 4 (z > 0); faces outward
CUBE_V = np.array([[x, y, z] for z in (-1.0, 1.0) for y in (-1.0, 1.0) for x in (-1.0, 1.0)])
CUBE_F = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
SEMI_EDGE = (4, 5)  # top face, y = -1 side: sharpness 1.5
SHARP_EDGE = (6, 7)  # top face, y = +1 side: infinitely sharp
FRACTIONAL_EDGE = (0, 2)  # bottom face, x = -1 side: sharpness 0.4 (pins Blender's crease mapping)
CORNER_VERTEX = 7


def creased_cube() -> Fixture:
    """A cube with one edge of sharpness 1.5 and, on the opposite side of the top face, one
    infinitely sharp edge (a chamfered-box look); plus one edge of sharpness 0.4 on the bottom,
    whose edge point is 0.4 of the way from the smooth point to the midpoint."""
    sharp = {SEMI_EDGE: 1.5, SHARP_EDGE: math.inf, FRACTIONAL_EDGE: 0.4}
    return Fixture("creased_cube", CUBE_V.copy(), [list(f) for f in CUBE_F], {"edge_sharpness": sharp},
                   "semi-sharp (1.5, 0.4) and infinitely sharp edges")


def corner_cube() -> Fixture:
    """A cube with one corner vertex of sharpness 2: it stays put for two levels, then smooths."""
    return Fixture("corner_cube", CUBE_V.copy(), [list(f) for f in CUBE_F],
                   {"vertex_sharpness": {CORNER_VERTEX: 2.0}}, "corner sharpness 2 at vertex 7")


def uv_cube() -> Fixture:
    """A cube with the standard cross unfolding: a column of four faces (front, top, back, bottom)
    with the left and right faces as flaps beside the top; 14 distinct UVs on a 3 x 4 grid
    of 1/4 cells (u in [0, 3/4], v in [0, 1]), per-corner UV indices, seams where the cross is cut."""
    v = CUBE_V.copy()
    # grid points (column i, row j) of the cross, in units of 1/4
    g = {}

    def uv(i: int, j: int) -> int:
        return g.setdefault((i, j), len(g))

    # faces with their corners' grid points (same vertex order as the face)
    front = ([0, 1, 5, 4], [(1, 0), (2, 0), (2, 1), (1, 1)])  # y = -1
    top = ([4, 5, 7, 6], [(1, 1), (2, 1), (2, 2), (1, 2)])  # z = +1
    back = ([6, 7, 3, 2], [(1, 2), (2, 2), (2, 3), (1, 3)])  # y = +1
    bottom = ([2, 3, 1, 0], [(1, 3), (2, 3), (2, 4), (1, 4)])  # z = -1
    left = ([0, 4, 6, 2], [(0, 1), (1, 1), (1, 2), (0, 2)])  # x = -1: flap on top's edge 4-6
    right = ([1, 3, 7, 5], [(3, 1), (3, 2), (2, 2), (2, 1)])  # x = +1: flap on top's edge 5-7
    faces, corner_uv = [], []
    for fv, fg in (front, top, back, bottom, left, right):
        faces.append(fv)
        corner_uv += [uv(*p) for p in fg]
    table = np.zeros((len(g), 2))
    for (i, j), k in g.items():
        table[k] = (i / 4.0, j / 4.0)
    uvs = table[np.array(corner_uv)]
    # each grid point is one cube vertex: a UV value never spans two vertices
    assert len({(fv[k], p) for fv, fg in (front, top, back, bottom, left, right) for k, p in enumerate(fg)}) == len(g)
    return Fixture("uv_cube", v, faces, {"uvs": uvs}, f"cross-unfolded cube: {len(g)} UVs, seams",
                   table, np.array(corner_uv))


def uv_grid(n: int = 4) -> Fixture:
    """:func:`quad_grid` with one UV chart and no seams, u = x^2, v = y per corner: the UV map is
    not affine, so a smooth face-varying rule moves interior UVs and linear rules do not."""
    fx = quad_grid(n)
    table = np.column_stack([fx.vertices[:, 0] ** 2, fx.vertices[:, 1]])
    index = np.array([i for f in fx.faces for i in f])
    return Fixture("uv_grid", fx.vertices, fx.faces, {"uvs": table[index]}, "open grid, one UV chart u = x^2, v = y",
                   table, index)


def mixed_closed() -> Fixture:
    """A closed pentagonal prism whose first side quad is split into two triangles: pentagons,
    quads and triangles in one closed mesh (an irregular vertex of each valence 3 and 4)."""
    n = 5
    v = [[math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n), z] for z in (-0.6, 0.6) for k in range(n)]
    faces = [list(range(n - 1, -1, -1)), list(range(n, 2 * n))]
    for k in range(n):
        a, b = k, (k + 1) % n
        if k == 0:
            faces += [[a, b, n + b], [a, n + b, n + a]]
        else:
            faces.append([a, b, n + b, n + a])
    return Fixture("mixed_closed", np.array(v), faces, {}, "closed: triangles, quads, pentagons")


ALL = {f.name: f for f in (quad_grid(), cylinder(), creased_cube(), corner_cube(), uv_cube(), uv_grid(), mixed_closed())}


def triangulated(fx: Fixture) -> Fixture:
    """``fx`` with each quad split along its first diagonal (corners 0-2) into two triangles, for
    Loop; edge and vertex sharpness stay on the same vertex pairs, UVs follow their corners.

    On :func:`quad_grid` this leaves two grid corners (``n`` and ``n (n + 1)``) in one triangle
    each, which are OpenSubdiv's corners for edge_and_corner, while the other two are in two
    triangles and follow the boundary curve rule in both boundary modes."""
    faces, corners = [], []
    c = 0
    for f in fx.faces:
        ids = list(range(c, c + len(f)))
        c += len(f)
        if len(f) == 4:
            faces += [[f[0], f[1], f[2]], [f[0], f[2], f[3]]]
            corners += [ids[0], ids[1], ids[2], ids[0], ids[2], ids[3]]
        else:
            faces.append(list(f))
            corners += ids
    options = dict(fx.options)
    if "uvs" in options:
        options["uvs"] = np.asarray(options["uvs"])[corners]
    index = None if fx.uv_index is None else fx.uv_index[corners]
    return Fixture(fx.name + "_tri", fx.vertices.copy(), faces, options, fx.about + " (triangulated)",
                   fx.uv_table, index)
