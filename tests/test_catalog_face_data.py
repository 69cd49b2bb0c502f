"""Face attributes through the remeshing catalog (issue 15): the Conway operators and
TopMod's schemes built through the keyed builder give every output face the attributes
of the input face it descends from (``src/schemes/face_parents.rs``).

The rule: a
face built inside input face f (a kis triangle, a shrunk copy, a corner pentagon) comes
from f; a face born around an input edge (chamfer's hexagons, join's quads) from the face
of the edge's first side; a face born around an input vertex (dual, ambo, truncate's
corner faces) from the lowest-index face around the vertex. Along a chain (``t = dkd``,
TopMod's "dual + X + dual", iterations) the parents compose, so truncate's octagons on
the cube keep their own square's data, and one call gives what several give.

Operators that keep a copy of every input face (an ``F`` term in F') or split every face
(kis, gyro) keep every input face's value; the others (dual, join, needle, ...) keep a
subset. The compositions with a scheme not built through the keyed builder (root3 =
dual + honeycomb + dual, dual_loop = dual + Loop + dual, doo_sabin_bc = split edges +
Doo-Sabin) take that scheme's parents from its correspondence (``origins``), under the
same rule.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable

import numpy as np
import pytest

import topomesh as tm

SEEDS = {"cube": tm.cube, "genus2": lambda: tm.genus_surface(2)}

CONWAY = {o["method"]: o for o in tm.conway_operators()}

# per-face children for every input face: an `F` term in F', or every face split
CONWAY_KEEPS_ALL = {m for m, o in CONWAY.items() if o["counts"][2].startswith("F")} | {"kis", "gyro"}

Op = Callable[[tm.Mesh], tm.Mesh]

TOPMOD: dict[str, tuple[Op, bool]] = {
    # name: (call, every input face keeps a child)
    "stellate": (lambda m: m.stellate(offset=0.1), True),
    "double_stellate": (lambda m: m.double_stellate(offset=0.1), True),
    "double_stellate_misc": (lambda m: m.double_stellate_misc(height=0.1, curve=0.1), False),
    "stellate_edge_removal": (lambda m: m.stellate_edge_removal(), False),
    "linear_vertex_insertion": (lambda m: m.linear_vertex_insertion(), True),
    "corner_cutting": (lambda m: m.corner_cutting(), True),
    "modified_corner_cutting": (lambda m: m.modified_corner_cutting(), True),
    "loop_style": (lambda m: m.loop_style(), True),
    "root4": (lambda m: m.root4(), True),
    "dual_loop_style": (lambda m: m.dual_loop_style(), True),
    "hexagon_preserving": (lambda m: m.hexagon_preserving(), True),
    "dual_hexagon_preserving": (lambda m: m.dual_hexagon_preserving(), True),
    "pentagonalize": (lambda m: m.pentagonalize(), True),
    "cubic_pentagonalize": (lambda m: m.cubic_pentagonalize(), True),
    "dual_pentagonalize": (lambda m: m.dual_pentagonalize(), True),
    "pentagon_preserving": (lambda m: m.pentagon_preserving(), True),
    "dual_pentagon_preserving": (lambda m: m.dual_pentagon_preserving(), False),
    "dual_12_6_4": (lambda m: m.dual_12_6_4(), True),
    "remesh_12_6_4": (lambda m: m.remesh_12_6_4(), False),
    "checkerboard": (lambda m: m.checkerboard(), True),
    "dual_checkerboard": (lambda m: m.dual_checkerboard(), True),
    "doo_sabin_bc_new": (lambda m: m.doo_sabin_bc_new(), True),
    "dome": (lambda m: m.dome(), True),
    "fractal": (lambda m: m.fractal(), True),
    "stellate x2": (lambda m: m.stellate(iterations=2), True),
    "corner_cutting x2": (lambda m: m.corner_cutting(iterations=2), True),
    "subdivide_faces": (lambda m: m.subdivide_faces([0, 1]), True),
    "subdivide_faces fans": (lambda m: m.subdivide_faces([0, 2], quads=False), True),
    "extrude": (lambda m: m.extrude([0, 3]), True),
    "extrude octahedral": (lambda m: m.extrude([1], kind="octahedral", segments=2), True),
    # through the origins of honeycomb, Loop and Doo-Sabin
    "root3": (lambda m: m.root3(), False),
    "root3 x2": (lambda m: m.root3(iterations=2), False),
    "dual_loop": (lambda m: m.dual_loop(), False),
    "doo_sabin_bc": (lambda m: m.doo_sabin_bc(), True),
}


def with_face_data(m: tm.Mesh) -> tm.Mesh:
    nf = len(m.face_sizes)
    rgb = np.c_[np.arange(nf) * 1.5, np.arange(nf) % 7, -np.arange(nf)].astype(float)
    return m.with_attributes(face={"id": np.arange(nf), "rgb": rgb})


def run_quiet(op: Op, m: tm.Mesh) -> tm.Mesh:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no GeometryWarning: face data is carried
        return op(m)


def check_inherited(m: tm.Mesh, out: tm.Mesh, keeps_all: bool) -> np.ndarray:
    nf = len(m.face_sizes)
    fa = out.face_attributes
    assert set(fa) == {"id", "rgb"}
    ids = fa["id"]
    assert ids.shape == (len(out.face_sizes),)
    assert ids.min() >= 0 and ids.max() < nf
    # the rows move together: the child's rgb is its parent's
    np.testing.assert_array_equal(fa["rgb"], m.face_attributes["rgb"][ids])
    assert not fa["id"].flags.writeable
    if keeps_all:
        assert set(ids.tolist()) == set(range(nf)), "every input face keeps a child"
    return ids


@pytest.mark.parametrize("seed", sorted(SEEDS))
@pytest.mark.parametrize("method", sorted(CONWAY))
def test_conway_faces_inherit(method: str, seed: str) -> None:
    m = with_face_data(SEEDS[seed]())
    out = run_quiet(lambda x: getattr(x, method)(), m)
    assert out == getattr(m.without_data(), method)()  # same mesh as without data
    check_inherited(m, out, method in CONWAY_KEEPS_ALL)


@pytest.mark.parametrize("seed", sorted(SEEDS))
@pytest.mark.parametrize("name", sorted(TOPMOD))
def test_topmod_faces_inherit(name: str, seed: str) -> None:
    op, keeps_all = TOPMOD[name]
    m = with_face_data(SEEDS[seed]())
    out = run_quiet(op, m)
    assert out == op(m.without_data())
    check_inherited(m, out, keeps_all)


def test_origin_built_parents_follow_the_rule() -> None:
    """root3 (dual + honeycomb + dual) on the cube: every output triangle is born around
    an input vertex (a honeycomb corner inside the dual face of that vertex), so it takes
    the data of the lowest face around that vertex; and
    doo_sabin_bc's first F faces (Doo-Sabin's face faces) keep their own face's."""
    m = with_face_data(tm.cube())
    sizes = m.face_sizes
    face_of_corner = np.repeat(np.arange(len(sizes)), sizes)
    lowest = {int(face_of_corner[m.face_indices == v].min()) for v in range(m.n_vertices)}
    assert len(lowest) < len(sizes)  # the check can fail: not every face is a lowest one
    ids = run_quiet(lambda x: x.root3(), m).face_attributes["id"]
    assert set(ids.tolist()) <= lowest
    ids = run_quiet(lambda x: x.doo_sabin_bc(), m).face_attributes["id"]
    np.testing.assert_array_equal(ids[: len(sizes)], np.arange(len(sizes)))


def nearest_face(m: tm.Mesh, points: np.ndarray) -> np.ndarray:
    c = m.face_centroids
    return np.argmin(((points[:, None, :] - c[None, :, :]) ** 2).sum(-1), axis=1)


@pytest.mark.parametrize(
    "op",
    [
        lambda m: m.kis(),
        lambda m: m.stellate(offset=0.2),
        lambda m: m.loft(),
        lambda m: m.gyro(),
        lambda m: m.quinto(),
        lambda m: m.linear_vertex_insertion(),
        lambda m: m.loop_style(),
        lambda m: m.extrude([2, 5]),
    ],
    ids=["kis", "stellate", "loft", "gyro", "quinto", "linear_vertex_insertion", "loop_style", "extrude"],
)
def test_children_lie_over_their_parent(op: Op) -> None:
    # on the cube every face built inside input face f is nearest to f's centroid
    m = with_face_data(tm.cube())
    out = run_quiet(op, m)
    ids = out.face_attributes["id"]
    np.testing.assert_array_equal(ids, nearest_face(m, out.face_centroids))


def test_truncate_keeps_each_face_and_gives_corners_an_adjacent_face() -> None:
    # t = dkd: the octagons are the squares (their own id, in order), the corner
    # triangles inherit a face around their corner (born around an input vertex)
    m = with_face_data(tm.cube())
    out = run_quiet(lambda x: x.truncate(), m)
    ids = out.face_attributes["id"]
    sizes = out.face_sizes
    assert (sizes[:6] == 8).all() and (sizes[6:] == 3).all()
    np.testing.assert_array_equal(ids[:6], np.arange(6))
    np.testing.assert_array_equal(ids[:6], nearest_face(m, out.face_centroids[:6]))
    faces = np.split(m.face_indices, np.cumsum(m.face_sizes)[:-1])
    corner = np.argmin(((out.face_centroids[6:, None, :] - m.vertices[None]) ** 2).sum(-1), axis=1)
    for v, f in zip(corner, ids[6:]):
        assert v in faces[f], (v, f)


def test_chamfer_edge_faces_take_an_adjacent_face() -> None:
    m = with_face_data(tm.cube())
    out = run_quiet(lambda x: x.chamfer(), m)
    ids = out.face_attributes["id"]
    np.testing.assert_array_equal(ids[:6], np.arange(6))  # the shrunk copies
    faces = [set(f) for f in np.split(m.face_indices, np.cumsum(m.face_sizes)[:-1])]
    edges = m.edges
    mid = m.vertices[edges].mean(axis=1)
    for c, f in zip(out.face_centroids[6:], ids[6:]):
        e = edges[np.argmin(((mid - c) ** 2).sum(-1))]
        assert set(e.tolist()) <= faces[f], "a hexagon inherits from a face of its edge"


def test_chains_compose() -> None:
    m = with_face_data(tm.genus_surface(2))
    a = run_quiet(lambda x: x.conway("dk"), m)
    b = run_quiet(lambda x: x.kis().dual(), m)
    c = run_quiet(lambda x: x.zip(), m)
    np.testing.assert_array_equal(a.face_attributes["id"], b.face_attributes["id"])
    np.testing.assert_array_equal(a.face_attributes["id"], c.face_attributes["id"])
    s2 = run_quiet(lambda x: x.stellate(iterations=2), m)
    ss = run_quiet(lambda x: x.stellate().stellate(), m)
    np.testing.assert_array_equal(s2.face_attributes["id"], ss.face_attributes["id"])
    # zero iterations: the same faces
    s0 = run_quiet(lambda x: x.stellate(iterations=0), m)
    np.testing.assert_array_equal(s0.face_attributes["id"], np.arange(len(m.face_sizes)))


def test_conway_function_with_a_seed_mesh_keeps_face_data() -> None:
    # topomesh.conway(notation, seed=m) is m.conway(notation), face data included
    m = with_face_data(tm.genus_surface(2))
    a = run_quiet(lambda x: tm.conway("dtk", seed=x), m)
    b = run_quiet(lambda x: x.conway("dtk"), m)
    assert a == b
    np.testing.assert_array_equal(a.face_attributes["id"], b.face_attributes["id"])
    check_inherited(m, a, False)
    # a seed letter beside a seed mesh is still refused
    with pytest.raises(tm.MeshError, match="seed"):
        tm.conway("dC", seed=m)


def test_other_data_is_still_named_and_dropped() -> None:
    c = tm.cube()
    m = c.with_creases({tuple(c.edges[0]): 2.0}).with_attributes(vertex={"w": np.arange(8.0)}, face={"id": np.arange(6)})
    with pytest.warns(tm.GeometryWarning) as rec:
        out = m.kis()
    msg = str(rec[0].message).split(" (this operator")[0]
    assert "creases" in msg and 'vertex attributes ["w"]' in msg and "face attributes" not in msg
    assert set(out.face_attributes) == {"id"} and not out.vertex_attributes


def test_input_is_not_modified() -> None:
    m = with_face_data(tm.cube())
    before = m.face_attributes["id"].copy()
    run_quiet(lambda x: x.truncate(), m)
    np.testing.assert_array_equal(m.face_attributes["id"], before)
