"""Creases, boundaries, attributes and correspondence of Catmull-Clark and Loop.

The OpenSubdiv comparisons are in ``test_opensubdiv.py``; this file checks
the API, the published rules on chosen vertices, and that everything the
schemes return agrees with itself: ``S @ P`` is the positions, attributes
are ``S @ A``, parents cover every output face.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import topomesh as tm
from topomesh import MeshError


def grid(n: int = 4) -> tm.Mesh:
    """An open n × n quad grid on a bumpy height field."""
    i, j = np.meshgrid(np.arange(n + 1.0), np.arange(n + 1.0))
    v = np.c_[i.ravel(), j.ravel(), 0.3 * np.sin(0.9 * i.ravel()) * np.cos(1.3 * j.ravel())]
    w = n + 1
    faces = [[a, a + 1, a + w + 1, a + w] for a in (r * w + c for r in range(n) for c in range(n))]
    return tm.Mesh.from_polygons(v, faces, close_boundaries=True)


def mixed() -> tm.Mesh:
    """A closed mesh of quads, triangles and pentagons (a cube with a roof)."""
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1], [0.5, 0, 1.6], [0.5, 1, 1.6]], float)
    faces = [[0, 3, 2, 1], [0, 1, 5, 8, 4], [3, 7, 9, 6, 2], [1, 2, 6, 5], [0, 4, 7, 3], [4, 8, 9, 7], [5, 6, 9, 8]]
    return tm.Mesh.from_polygons(v, faces)


MESHES = {"cube": tm.cube, "torus": lambda: tm.torus(6, 4), "grid": grid, "mixed": mixed, "tetrahedron": tm.tetrahedron}
SCHEMES = ["catmull_clark", "loop"]


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("name", sorted(MESHES))
@pytest.mark.parametrize("levels", [1, 3])
def test_matrix_reproduces_positions_and_attributes(scheme: str, name: str, levels: int) -> None:
    m = MESHES[name]()
    rng = np.random.default_rng(1)
    colour, height = rng.random((m.n_vertices, 3)), rng.random(m.n_vertices)
    ma = m.with_attributes(vertex={"colour": colour, "height": height})
    out, corr = getattr(ma, scheme)(levels, correspondence=True)
    plain = getattr(m, scheme)(levels)
    assert out == plain  # attributes change nothing else
    S = corr.matrix
    assert S.shape == (out.n_vertices, m.n_vertices)
    np.testing.assert_allclose(S @ m.vertices, out.vertices, atol=1e-12)
    np.testing.assert_allclose(S.sum(axis=1), 1.0, atol=1e-12)  # affine: rows sum to one
    np.testing.assert_allclose(out.vertex_attributes["colour"], S @ colour, atol=1e-12)
    np.testing.assert_allclose(out.vertex_attributes["height"], S @ height, atol=1e-12)
    assert out.vertex_attributes["height"].shape == (out.n_vertices,)
    np.testing.assert_allclose(corr.apply(colour), S @ colour, atol=1e-12)
    # the input is untouched
    np.testing.assert_array_equal(ma.vertex_attributes["colour"], colour)


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("name", sorted(MESHES))
def test_parents_cover_every_output_face(scheme: str, name: str) -> None:
    m = MESHES[name]()
    mat = np.arange(len(m.face_sizes)) * 10
    out, corr = getattr(m.with_attributes(face={"material": mat}), scheme)(2, correspondence=True)
    n_out = len(out.face_sizes)
    assert corr.face_parents.shape == (n_out,) and (corr.face_parents >= 0).all()
    np.testing.assert_array_equal(out.face_attributes["material"], mat[corr.face_parents])
    # every face splits into as many children as the scheme's count formula says
    per_level = 4
    sizes = m.face_sizes
    if scheme == "catmull_clark":
        want = sizes * per_level
    else:
        want = np.where(sizes == 3, 16, sizes * 16)
    np.testing.assert_array_equal(np.bincount(corr.face_parents, minlength=len(sizes)), want)
    assert (corr.face_kinds == tm.correspondence.FACE).all()


@pytest.mark.parametrize("scheme", SCHEMES)
def test_vertex_origins_follow_the_layout(scheme: str) -> None:
    m = tm.cube() if scheme == "catmull_clark" else tm.icosahedron()
    out, corr = getattr(m, scheme)(1, correspondence=True)
    V, E, F = m.n_vertices, m.n_edges, m.n_faces
    kinds = corr.vertex_kinds
    assert (kinds[:V] == 0).all() and (kinds[V : V + E] == 1).all() and (kinds[V + E :] == 2).all()
    assert len(kinds) == V + E + (F if scheme == "catmull_clark" else 0)
    np.testing.assert_array_equal(corr.vertex_origins[V : V + E], np.arange(E))
    # an edge point lies between its edge's ends; its row weights them
    S = corr.matrix.toarray()
    a, b = m.edges[3]
    assert S[V + 3, a] > 0 and S[V + 3, b] > 0


def test_zero_levels_is_the_identity() -> None:
    m = tm.cube().with_creases({(0, 1): 2.0})
    out, corr = m.catmull_clark(0, correspondence=True)
    assert out == m
    np.testing.assert_array_equal(out.edge_sharpness, m.edge_sharpness)
    np.testing.assert_array_equal(corr.matrix.toarray(), np.eye(8))
    np.testing.assert_array_equal(corr.face_parents, np.arange(6))


def test_with_creases_accepts_arrays_and_pairs() -> None:
    c = tm.cube()
    a, b = c.edges[5]
    s = np.zeros(c.n_edges)
    s[5] = 1.5
    assert (c.with_creases(s).edge_sharpness == c.with_creases({(b, a): 1.5}).edge_sharpness).all()
    assert c.with_creases({(a, b): np.inf}).edge_sharpness[5] == np.inf
    assert c.with_creases({(a, b): 12.0}).edge_sharpness[5] == np.inf  # >= 10 is infinite, as in OpenSubdiv
    v = c.with_creases(vertex_sharpness={3: 2.0}).vertex_sharpness
    assert v[3] == 2.0 and v.sum() == 2.0
    assert (c.edge_sharpness == 0).all() and (c.vertex_sharpness == 0).all()


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"edge_sharpness": {(0, 6): 1.0}}, r"\(0, 6\) is not an edge"),
        ({"edge_sharpness": np.full(12, -1.0)}, "must be >= 0"),
        ({"edge_sharpness": np.full(12, np.nan)}, "must be >= 0"),
        ({"edge_sharpness": np.ones(11)}, "11 edge sharpness values for 12 edges"),
        ({"vertex_sharpness": {8: 1.0}}, "vertex 8 out of range"),
        ({"edge_sharpness": {(0, 1): "x"}}, "not a number"),
    ],
)
def test_bad_creases_are_refused(kwargs: dict, match: str) -> None:
    with pytest.raises(MeshError, match=match):
        tm.cube().with_creases(**kwargs)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"vertex": {"c": np.ones((7, 3))}}, r"shape \(7, 3\), expected \(8, k\)"),
        ({"vertex": {"c": np.array(["a"] * 8)}}, "numbers expected"),
        ({"vertex": {"c": np.r_[np.ones(7), np.inf]}}, "not finite at vertex 7"),
        ({"face": {"m": np.ones(5)}}, "expected first axis 6"),
    ],
)
def test_bad_attributes_are_refused(kwargs: dict, match: str) -> None:
    with pytest.raises(MeshError, match=match):
        tm.cube().with_attributes(**kwargs)


def test_bad_options_are_refused() -> None:
    with pytest.raises(MeshError, match='boundary = "corner"'):
        tm.cube().catmull_clark(boundary="corner")
    with pytest.raises(MeshError, match="crease_method"):
        tm.cube().loop(crease_method="sharp")


def test_mark_creases_by_dihedral_angle() -> None:
    c = tm.cube()
    assert (c.mark_creases(30).edge_sharpness == np.inf).all()
    assert (c.mark_creases(95).edge_sharpness == 0).all()
    t = tm.torus(48, 24)
    assert (t.mark_creases(30).edge_sharpness == 0).all()
    assert (c.mark_creases(30, sharpness=2.0).edge_sharpness == 2.0).all()
    with pytest.raises(MeshError, match="angle"):
        c.mark_creases(200)


def edge_midpoint(m: tm.Mesh, e: int) -> np.ndarray:
    a, b = m.edges[e]
    return (m.vertices[a] + m.vertices[b]) / 2


@pytest.mark.parametrize("scheme", SCHEMES)
def test_infinitely_sharp_edges_stay_straight(scheme: str) -> None:
    m = tm.cube() if scheme == "catmull_clark" else tm.octahedron()
    e = 0
    creased = m.with_creases({tuple(m.edges[e]): np.inf})
    out = getattr(creased, scheme)(1)
    V = m.n_vertices
    np.testing.assert_allclose(out.vertices[V + e], edge_midpoint(m, e), atol=1e-12)
    # the crease carries on: its two children are infinitely sharp, nothing else
    assert np.isinf(out.edge_sharpness).sum() == 2 and (out.edge_sharpness[~np.isinf(out.edge_sharpness)] == 0).all()
    # a smooth edge point differs from its midpoint
    assert np.linalg.norm(out.vertices[V + 1] - edge_midpoint(m, 1)) > 1e-3


def test_semi_sharp_crease_blends_by_its_fractional_part() -> None:
    c = tm.cube()
    e = 2
    key = tuple(c.edges[e])
    smooth = c.catmull_clark(1).vertices[c.n_vertices + e]
    mid = edge_midpoint(c, e)
    for s in (0.25, 0.5, 0.75):
        p = c.with_creases({key: s}).catmull_clark(1).vertices[c.n_vertices + e]
        np.testing.assert_allclose(p, s * mid + (1 - s) * smooth, atol=1e-12)
    # sharpness 1.5: a crease at level 1, its children (0.5) blend at level 2
    one = c.with_creases({key: 1.5}).catmull_clark(1)
    np.testing.assert_allclose(one.vertices[c.n_vertices + e], mid, atol=1e-12)
    assert sorted(one.edge_sharpness[one.edge_sharpness > 0]) == [0.5, 0.5]
    two = one.catmull_clark(1)
    assert (two.edge_sharpness == 0).all()
    # two levels in one call equal two calls of one level
    both = c.with_creases({key: 1.5}).catmull_clark(2)
    np.testing.assert_allclose(both.vertices, two.vertices, atol=1e-12)


def test_crease_vertex_rule_and_corner() -> None:
    c = tm.cube()
    # a crease through vertex 0: two of its edges sharp
    e0 = [i for i, (a, b) in enumerate(c.edges) if 0 in (a, b)]
    ends = [int(b if a == 0 else a) for a, b in c.edges[e0[:2]]]
    creased = c.with_creases({tuple(c.edges[i]): np.inf for i in e0[:2]})
    p = creased.catmull_clark(1).vertices[0]
    want = (6 * c.vertices[0] + c.vertices[ends[0]] + c.vertices[ends[1]]) / 8
    np.testing.assert_allclose(p, want, atol=1e-12)
    # all three sharp, or a sharp vertex: a corner stays put
    for m in (c.with_creases({tuple(c.edges[i]): np.inf for i in e0}), c.with_creases(vertex_sharpness={0: np.inf})):
        np.testing.assert_allclose(m.catmull_clark(1).vertices[0], c.vertices[0], atol=1e-12)
        np.testing.assert_allclose(m.loop(1).vertices[0], c.vertices[0], atol=1e-12)
    # a semi-sharp vertex of sharpness 2 is a corner for two levels, then smooth
    m = c.with_creases(vertex_sharpness={0: 2.0}).catmull_clark(2)
    np.testing.assert_allclose(m.vertices[0], c.vertices[0], atol=1e-12)
    assert m.vertex_sharpness[0] == 0.0
    assert np.linalg.norm(m.catmull_clark(1).vertices[0] - c.vertices[0]) > 1e-3


def test_chaikin_averages_neighbouring_creases() -> None:
    c = tm.cube()
    e0 = [i for i, (a, b) in enumerate(c.edges) if 0 in (a, b)][:2]
    s = {tuple(c.edges[e0[0]]): 1.5, tuple(c.edges[e0[1]]): 3.5}
    uni = c.with_creases(s).catmull_clark(1)
    chk = c.with_creases(s).catmull_clark(1, crease_method="chaikin")
    # at vertex 0 Chaikin gives 0.75·1.5 + 0.25·3.5 − 1 = 1.0 and 0.75·3.5 + 0.25·1.5 − 1 = 2.0 (uniform: 0.5, 2.5)
    def at_vertex_0(m: tm.Mesh) -> list[float]:
        return sorted(m.edge_sharpness[(m.edges == 0).any(axis=1) & (m.edge_sharpness > 0)].tolist())
    assert at_vertex_0(uni) == [0.5, 2.5]
    assert at_vertex_0(chk) == pytest.approx([1.0, 2.0])
    # a lone crease decays the same way in both methods
    lone = {tuple(c.edges[e0[0]]): 2.5}
    np.testing.assert_array_equal(c.with_creases(lone).catmull_clark(1).edge_sharpness, c.with_creases(lone).catmull_clark(1, crease_method="chaikin").edge_sharpness)


def triangle_grid(n: int = 3) -> tm.Mesh:
    """The grid with every quad split along the same diagonal (corners 3 and 12 have one triangle)."""
    g = grid(n)
    q = g.face_indices.reshape(-1, 4)
    tris = np.r_[q[:, [0, 1, 2]], q[:, [0, 2, 3]]]
    return tm.Mesh.from_polygons(g.vertices, tris, close_boundaries=True)


@pytest.mark.parametrize("scheme", SCHEMES)
def test_open_grid_boundary_options(scheme: str) -> None:
    # Loop's corners are those of the triangles it runs on: a vertex with one
    # triangle (a quad's corner becomes two triangles of the fan)
    g = grid(3) if scheme == "catmull_clark" else triangle_grid(3)
    corners = [0, 3, 12, 15] if scheme == "catmull_clark" else [3, 12]
    for levels in (1, 2):
        out = getattr(g, scheme)(levels)
        assert out.n_holes == 1
        np.testing.assert_allclose(out.vertices[corners], g.vertices[corners], atol=1e-12)
    out = getattr(g, scheme)(1, boundary="edge_only")
    # with edge_only, corner 3 (boundary neighbours 2 and 7) follows the crease rule
    np.testing.assert_allclose(out.vertices[3], (6 * g.vertices[3] + g.vertices[2] + g.vertices[7]) / 8, atol=1e-12)
    # a boundary vertex with two faces follows the crease rule in both modes
    np.testing.assert_allclose(getattr(g, scheme)(1).vertices[1], (6 * g.vertices[1] + g.vertices[0] + g.vertices[2]) / 8, atol=1e-12)
    # edge points of boundary edges are midpoints
    V = g.n_vertices
    for e, (a, b) in enumerate(g.edges):
        if (a in (0, 1, 2, 3)) and (b in (0, 1, 2, 3)):
            np.testing.assert_allclose(out.vertices[V + e], (g.vertices[a] + g.vertices[b]) / 2, atol=1e-12)


@pytest.mark.parametrize("scheme", SCHEMES)
def test_open_meshes_stay_open_for_peers(scheme: str) -> None:
    trimesh = pytest.importorskip("trimesh")
    g = grid(3)
    out = getattr(g, scheme)(2)
    t = out.to_trimesh()
    assert not t.is_watertight
    # the boundary: edges used by one triangle
    e = np.sort(t.edges, axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    assert (counts == 1).sum() == 12 * 4  # 12 boundary edges, each split in two per level
    assert trimesh.Trimesh(out.vertices, out.triangles(), process=False).euler_number == 1


def test_data_survives_pickle_and_with_vertices() -> None:
    c = tm.cube().with_creases({(0, 1): 1.5}, {2: 3.0}).with_attributes(vertex={"w": np.arange(8.0)}, face={"m": np.arange(6)})
    p = pickle.loads(pickle.dumps(c))
    assert p == c
    np.testing.assert_array_equal(p.edge_sharpness, c.edge_sharpness)
    np.testing.assert_array_equal(p.vertex_sharpness, c.vertex_sharpness)
    np.testing.assert_array_equal(p.vertex_attributes["w"], c.vertex_attributes["w"])
    np.testing.assert_array_equal(p.face_attributes["m"], c.face_attributes["m"])
    moved = c.with_vertices(c.vertices * 2)
    np.testing.assert_array_equal(moved.edge_sharpness, c.edge_sharpness)
    assert set(moved.vertex_attributes) == {"w"}
    assert c.without_data().vertex_attributes == {}
    with pytest.raises(ValueError):
        c.vertex_attributes["w"][0] = 1.0  # read-only


def test_repose_through_the_matrix() -> None:
    """Re-posing: ``S @ deformed`` equals subdividing the deformed coarse mesh."""
    t = tm.torus(8, 6)
    out, corr = t.catmull_clark(2, correspondence=True)
    twist = t.vertices.copy()
    ang = 0.4 * twist[:, 2]
    twist[:, 0], twist[:, 1] = np.cos(ang) * t.vertices[:, 0] - np.sin(ang) * t.vertices[:, 1], np.sin(ang) * t.vertices[:, 0] + np.cos(ang) * t.vertices[:, 1]
    np.testing.assert_allclose(corr.matrix @ twist, t.with_vertices(twist).catmull_clark(2).vertices, atol=1e-12)


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("name", ["cube", "torus", "grid"])
def test_limit_points_do_not_move_under_refinement(scheme: str, name: str) -> None:
    m = MESHES[name]()
    p, n = m.limit_points(scheme)
    q, k = getattr(m, scheme)(1).limit_points(scheme)
    np.testing.assert_allclose(p, q[: m.n_vertices], atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-12)
    # a deep refinement's vertex points converge to the limit points
    deep = getattr(m, scheme)(6).vertices[: m.n_vertices]
    assert np.abs(deep - p).max() < 2e-3 * np.abs(m.vertices).max()
    assert np.abs(m.vertices - p).max() > 1e-2  # and the limit differs from the control points


def test_limit_normals_agree_with_a_fine_mesh() -> None:
    t = tm.torus(8, 6)
    p, n = t.limit_points()
    fine = t.catmull_clark(5)
    fn = fine.vertex_normals[: t.n_vertices]
    assert (np.einsum("ij,ij->i", n, fn / np.linalg.norm(fn, axis=1)[:, None]) > np.cos(np.radians(1.0))).all()


def test_limit_points_respect_creases_and_corners() -> None:
    c = tm.cube().with_creases(vertex_sharpness={0: np.inf})
    p, _ = c.limit_points()
    np.testing.assert_array_equal(p[0], c.vertices[0])
    g = grid(3)
    p, _ = g.limit_points()
    np.testing.assert_array_equal(p[[0, 3, 12, 15]], g.vertices[[0, 3, 12, 15]])
    p2, _ = g.limit_points(boundary="edge_only")
    assert np.linalg.norm(p2[0] - g.vertices[0]) > 1e-3
    with pytest.raises(MeshError, match="scheme"):
        g.limit_points("doo_sabin")


def test_corner_attributes_follow_seams_and_survive_pickle() -> None:
    c = tm.cube()
    uv = np.c_[np.arange(24) % 4, np.arange(24) // 4].astype(float)  # every face its own chart
    m = c.with_attributes(corner={"uv": uv})
    out = m.catmull_clark(1)
    got = out.corner_attributes["uv"]
    assert got.shape == (96, 2)
    # 'all' is bilinear: each child quad's corner at the face point has its face's mean UV
    means = uv.reshape(6, 4, 2).mean(axis=1)
    np.testing.assert_allclose(got.reshape(24, 4, 2)[:, 2], np.repeat(means, 4, axis=0), atol=1e-12)
    p = pickle.loads(pickle.dumps(m))
    np.testing.assert_array_equal(p.corner_attributes["uv"], uv)
    # the schemes without face-varying rules carry them too (tests/test_face_varying_all.py)
    assert m.doo_sabin().corner_attributes["uv"].shape == (96, 2)
    with pytest.raises(MeshError, match=r"shape \(23, 2\)"):
        c.with_attributes(corner={"uv": uv[:23]})
    with pytest.raises(MeshError, match="outside the table"):
        c.with_attributes(corner={"uv": (uv[:4], np.arange(24))})
    with pytest.raises(MeshError, match="corner_interpolation"):
        m.catmull_clark(corner_interpolation="bilinear")


ALL_SCHEMES = {
    "catmull_clark": {}, "loop": {}, "doo_sabin": {}, "sqrt3": {}, "simplest": {}, "midpoint": {}, "dual": {},
    "honeycomb": {}, "vertex_truncation": {}, "vertex_truncation_polyhedral": {"mode": "polyhedral", "ratio": 0.3}, "sierpinski": {},
}


def run(m: tm.Mesh, scheme: str, levels: int, **kw):
    name = scheme.replace("_polyhedral", "")
    return getattr(m, name)(levels, **ALL_SCHEMES[scheme], **kw)


@pytest.mark.parametrize("scheme", sorted(ALL_SCHEMES))
@pytest.mark.parametrize("name", ["cube", "torus", "mixed"])
def test_every_scheme_has_a_matrix_and_parents(scheme: str, name: str) -> None:
    """Attribute interpolation equals S @ attribute, S @ P the positions, and parents
    cover every output face, for every linear scheme (issue 15's 'done when')."""
    m = MESHES[name]()
    rng = np.random.default_rng(2)
    a = rng.random((m.n_vertices, 2))
    mat = np.arange(len(m.face_sizes))
    levels = 1 if scheme == "sierpinski" else 2
    out, corr = run(m.with_attributes(vertex={"a": a}, face={"m": mat}), scheme, levels, correspondence=True)
    assert out == run(m, scheme, levels)
    S = corr.matrix
    np.testing.assert_allclose(S @ m.vertices, out.vertices, atol=1e-12)
    np.testing.assert_allclose(out.vertex_attributes["a"], S @ a, atol=1e-12)
    assert corr.face_parents.shape == (len(out.face_sizes),) and (corr.face_parents >= 0).all()
    np.testing.assert_array_equal(out.face_attributes["m"], mat[corr.face_parents])
    assert set(np.unique(corr.vertex_kinds)) <= {0, 1, 2} and len(corr.vertex_kinds) == out.n_vertices
    # every origin index is in range for its kind
    lim = {0: m.n_vertices, 1: m.n_edges, 2: len(m.face_sizes)}
    for kinds, idx in ((corr.vertex_kinds, corr.vertex_origins), (corr.face_kinds, corr.face_origins)):
        for k, n in lim.items():
            assert ((idx[kinds == k] >= 0) & (idx[kinds == k] < n)).all()


@pytest.mark.parametrize("scheme", ["catmull_clark", "loop", "doo_sabin", "midpoint", "dual", "honeycomb", "vertex_truncation", "sqrt3", "simplest"])
@pytest.mark.parametrize("fixture", ["disk", "annulus", "cylinder", "genus2_three_holes"])
def test_open_inputs_keep_chi_and_boundaries(scheme: str, fixture: str) -> None:
    from tests import open_meshes

    m = open_meshes.mesh(fixture)
    out, corr = run(m, scheme, 2, correspondence=True)
    out.validate()
    assert out.n_boundary_loops == m.n_boundary_loops and out.genus == m.genus
    assert out.euler_characteristic == m.euler_characteristic
    np.testing.assert_allclose(corr.matrix @ m.vertices, out.vertices, atol=1e-12)
    assert len(corr.face_parents) == len(out.face_sizes)


@pytest.mark.parametrize("scheme", ["sierpinski"])
def test_schemes_without_boundary_rules_refuse_open_inputs(scheme: str) -> None:
    from tests import open_meshes

    with pytest.raises(MeshError, match=rf"^{scheme}: the mesh has 1 boundary loop"):
        run(open_meshes.mesh("disk"), scheme, 1)


@pytest.mark.parametrize("name", ["cube", "torus"])
# (the torus's second iteration has its depth reduced where it would cross)
@pytest.mark.filterwarnings("ignore::topomesh.GeometryWarning")
def test_menger_carries_attributes_and_correspondence(name: str) -> None:
    """Menger's positions are not linear, but every output element has an origin:
    face data follows the parent faces, vertex data the transfer (copy from the vertex
    whose rule placed a point, linear along the edge for trisection points)."""
    m = MESHES[name]()
    rng = np.random.default_rng(5)
    a = rng.random((m.n_vertices, 3))
    mat = np.arange(len(m.face_sizes)) * 10
    d = m.with_attributes(vertex={"a": a, "pos": m.vertices}, face={"mat": mat})
    out, corr = d.menger(2, correspondence=True)
    assert out == m.menger(2)
    assert corr.linear is False and len(corr.face_parents) == len(out.face_sizes)
    np.testing.assert_array_equal(out.face_attributes["mat"], mat[corr.face_parents])
    np.testing.assert_allclose(out.vertex_attributes["a"], corr.apply(a), atol=1e-12)
    T = corr.transfer
    np.testing.assert_allclose(T @ np.ones(m.n_vertices), 1.0)
    # the input vertices keep their values
    np.testing.assert_allclose(out.vertex_attributes["a"][: m.n_vertices], a)
    # one level: carried positions are the owner vertex's, or exact on the edge for trisection points
    one, c1 = d.menger(1, correspondence=True)
    carried = one.vertex_attributes["pos"]
    on_edge = c1.vertex_kinds == 1
    assert on_edge.sum() == 2 * m.n_edges
    np.testing.assert_allclose(carried[on_edge], one.vertices[on_edge], atol=1e-12)
    at_vertex = c1.vertex_kinds == 0
    np.testing.assert_allclose(carried[at_vertex], m.vertices[c1.vertex_origins[at_vertex]], atol=1e-12)
    with pytest.raises(MeshError, match=r"^Correspondence.matrix: menger .* not linear"):
        corr.matrix
    # every output vertex and face names an input element of the right range
    lim = {0: m.n_vertices, 1: m.n_edges, 2: len(m.face_sizes)}
    for kinds, idx in ((corr.vertex_kinds, corr.vertex_origins), (corr.face_kinds, corr.face_origins)):
        for k, n in lim.items():
            assert ((idx[kinds == k] >= 0) & (idx[kinds == k] < n)).all()
    # every input face owns at least its 3n remeshing and pipe quads
    owned = np.bincount(c1.face_origins[c1.face_kinds == 2], minlength=len(m.face_sizes))
    assert (owned >= 3 * m.face_sizes).all()


def test_menger_carries_corner_attributes() -> None:
    c = tm.cube()
    uv = np.c_[np.arange(24) % 4, np.arange(24) // 4].astype(float)
    out = c.with_attributes(corner={"uv": uv}).menger()
    assert out.corner_attributes["uv"].shape == (len(out.face_indices), 2)
    assert set(np.unique(out.corner_attributes["uv"][:, 1])) <= set(range(6))  # no value crosses a face


def test_sqrt3_refines_the_boundary_every_second_level() -> None:
    """Kobbelt's boundary rule (2000, section 4): odd levels keep the boundary (its
    vertices do not move), even levels trisect every boundary edge."""
    from tests import open_meshes

    m = open_meshes.mesh("disk")
    nb = m.boundary_edges().shape[0]
    one = m.sqrt3()
    assert one.boundary_edges().shape[0] == nb
    loop = m.boundary_loops()[0]
    np.testing.assert_array_equal(one.vertices[loop], m.vertices[loop])
    two = m.sqrt3(iterations=2)
    assert two.boundary_edges().shape[0] == 3 * nb
    assert two.n_boundary_loops == 1 and two.euler_characteristic == m.euler_characteristic
    assert (two.face_sizes == 3).all()
    # one level at a time is an odd level each time: the boundary is never refined
    assert one.sqrt3().boundary_edges().shape[0] == nb


def test_simplest_keeps_the_boundary_polyline() -> None:
    """The mid-edge scheme on an open mesh: boundary vertices stay, boundary edges are
    split at their midpoints (topomesh's convention; the paper has no boundary rule)."""
    from tests import open_meshes

    m = open_meshes.mesh("annulus")
    out = m.simplest()
    assert out.n_boundary_loops == m.n_boundary_loops
    assert out.boundary_edges().shape[0] == 2 * m.boundary_edges().shape[0]
    kept = {tuple(p) for p in m.vertices[np.unique(m.boundary_edges())]}
    mids = {tuple(p) for p in m.vertices[m.boundary_edges()].mean(axis=1)}
    got = {tuple(p) for p in out.vertices[np.unique(out.boundary_edges())]}
    assert got == kept | mids


@pytest.mark.parametrize(
    "op",
    [
        lambda m: m.insert_edge(0, 0, 0, 2),
        lambda m: m.delete_edge(0),
        lambda m: m.subdivide_edge(0, 0.5),
        lambda m: m.collapse_edge(0),
        lambda m: m.create_vertex([0.0, 0.0, 0.0]),
        lambda m: m.rind(0.1),
    ],
    ids=["insert_edge", "delete_edge", "subdivide_edge", "collapse_edge", "create_vertex", "rind"],
)
def test_operators_announce_dropped_data(op) -> None:
    """The local operators keep positions only; a mesh with data says so instead of
    losing it silently, and a mesh without data stays quiet."""
    c = tm.cube()
    op(c)  # no warning (filterwarnings=error)
    d = c.with_attributes(vertex={"a": np.arange(8.0)})
    with pytest.warns(tm.GeometryWarning, match=r'does not carry the input\'s vertex attributes \["a"\]'):
        op(d)
