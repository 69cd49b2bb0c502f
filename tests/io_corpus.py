"""The shared corpus of the file tests (tests/test_io.py, tests/test_ply.py):
meshes with multi-edges, self-loops, two-gons, point-spheres, holes, any genus
and faces over 255 corners, and the equality a lossless round trip must keep."""

from __future__ import annotations

import numpy as np

import topomesh
from topomesh import Mesh

T = topomesh
EMPTY = Mesh.from_flat(np.zeros((0, 3)), [], [])


def _point_sphere():
    return EMPTY.create_vertex([0.0, 0.0, 0.0])[0]


def _two_two_gons():
    # a sphere of two 2-gons: two edges between vertices 0 and 1
    return Mesh.from_flat([[0.0, 0, 0], [1, 0, 0]], [2, 2], [0, 1, 1, 0], twins=[2, 3, 0, 1])


def _beach_ball(turn: int):
    """Three 2-gons on one vertex pair glued in a 3-cycle: the two cycles
    give two different valid spheres with the same polygon list."""
    a_to_b = [0, 2, 4]  # corner of face i running 0 -> 1
    twins = [0] * 6
    for i in range(3):
        j = (i + turn) % 3
        twins[a_to_b[i]] = 2 * j + 1
        twins[2 * j + 1] = a_to_b[i]
    return Mesh.from_flat([[0.0, 0, 0], [1, 0, 0]], [2, 2, 2], [0, 1] * 3, twins=twins)


def _corpus():
    h = T.cube().insert_edge(0, 0, 1, 0)[0]
    tet1 = T.tetrahedron().sierpinski()
    open_pair = Mesh.from_polygons(np.eye(4)[:, :3], [[0, 1, 2], [0, 2, 3]], close_boundaries=True)
    open_cube = Mesh.from_polygons(T.cube().vertices, _faces(T.cube())[1:], close_boundaries=True)
    return {
        "tetrahedron": T.tetrahedron(),
        "cube": T.cube(),
        "octahedron": T.octahedron(),
        "dodecahedron": T.dodecahedron(),
        "icosahedron": T.icosahedron(),
        "torus": T.torus(6, 4),
        "genus2": T.genus_surface(2),
        "tet_sierpinski1": tet1,
        "tet_sierpinski2": T.tetrahedron().sierpinski(2),
        "cube_sierpinski1": T.cube().sierpinski(),
        "tet_sierpinski_cc": tet1.catmull_clark(),
        "tet_sierpinski_sqrt3": tet1.sqrt3(),
        "tet_sierpinski_ds": tet1.doo_sabin(),
        "oct_sierpinski_cc": T.octahedron().sierpinski().catmull_clark(),
        "handle": h,
        "handle_sqrt3": h.sqrt3(),
        "handle_cc": h.catmull_clark(),
        "handle_ds": h.doo_sabin(),
        "cube_and_point": T.cube().create_vertex([5.0, 5.0, 5.0])[0],
        "point_sphere": _point_sphere(),
        "self_loop_sphere": _point_sphere().insert_edge(0, 0, 0, 0)[0],
        "two_two_gons": _two_two_gons(),
        "beach_ball": _beach_ball(1),
        "open_pair": open_pair,
        "open_cube": open_cube,
        "empty": EMPTY,
        # faces over 255 corners: PLY counts become uint
        "pillow300": Mesh.from_polygons(
            np.c_[np.cos(np.arange(300) / 47.0), np.sin(np.arange(300) / 47.0), np.zeros(300)],
            [list(range(300)), list(range(299, -1, -1))],
        ),
    }


def _faces(m):
    return np.split(np.asarray(m.face_indices), np.cumsum(m.face_sizes)[:-1])


CORPUS = _corpus()
NAMES = sorted(CORPUS)


def _same(a: Mesh, b: Mesh):
    assert b == a
    b.validate()
    assert (b.n_vertices, b.n_edges, b.n_faces, b.n_holes, b.genus) == (a.n_vertices, a.n_edges, a.n_faces, a.n_holes, a.genus)
