"""Corner (face-varying) attributes through every scheme (issue 15, part 4).

Catmull-Clark and Loop subdivide corner data on its face-varying mesh with OpenSubdiv's rules
(tests/test_creases.py, tests/test_opensubdiv.py, tests/test_face_varying_osd.py); every other
scheme carries it with the generic corner transfer of ``src/schemes/corner_transfer.rs``: each
output corner reads its vertex's stencil row with the corner values of one input face (on closed
meshes the schemes read the same values off their output numbering, ``src/schemes/corner_direct/``).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import topomesh as tm
from tests import open_meshes
from tests.osd import fixtures as F

# (method, keywords, the scheme's rows all lie in one face, so seamless data gives S @ a)
SCHEMES = {
    "doo_sabin": ({}, True),
    "sqrt3": ({}, False),  # vertex smoothing over the one-ring: corner data read linearly there
    "simplest": ({}, True),
    "midpoint": ({}, True),
    "dual": ({}, True),
    "honeycomb": ({}, True),
    "vertex_truncation": ({}, True),
    "sierpinski": ({}, True),
    "menger": ({}, True),
}
NAMES = list(SCHEMES)


def run(mesh: tm.Mesh, name: str, iterations: int = 1, **extra):
    kw, _ = SCHEMES[name]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tm.GeometryWarning)  # menger's crossing check on coarse input
        return getattr(mesh, name)(iterations, **kw, **extra)


def uv_cube() -> tuple[tm.Mesh, np.ndarray]:
    fx = F.uv_cube()
    return tm.Mesh.from_polygons(fx.vertices, fx.faces), fx.options["uvs"]


def corner_faces(m: tm.Mesh) -> np.ndarray:
    return np.repeat(np.arange(len(m.face_sizes)), m.face_sizes)


def one_hot(m: tm.Mesh) -> np.ndarray:
    """A per-corner indicator of its face: (C, F), every edge a seam."""
    return np.eye(len(m.face_sizes))[corner_faces(m)]


@pytest.mark.parametrize("iterations", [1, 2])
@pytest.mark.parametrize("name", NAMES)
def test_uv_cube_with_seams_goes_through(name, iterations):
    """One value per output corner (closed output: C = H = 2E), in the cross's UV box, and the
    per-face indicator stays an indicator: no output corner mixes two input faces' values (per
    level: the input of the second level is the first's output, with an indicator of its faces)."""
    m, uv = uv_cube()
    src = first = m.with_attributes(corner={"uv": uv, "chart": one_hot(m), "s": uv[:, 0]})
    if iterations == 2:
        one = run(src, name, 1)
        src = one.with_attributes(corner={"chart": one_hot(one)})
    out = run(src, name, 1)
    ca = out.corner_attributes
    assert ca["uv"].shape == (len(out.face_indices), 2) == (2 * out.n_edges, 2)
    assert ca["s"].shape == (2 * out.n_edges,)
    np.testing.assert_array_equal(ca["s"], ca["uv"][:, 0])
    assert (ca["uv"] >= -1e-12).all() and (ca["uv"] <= [0.75 + 1e-12, 1 + 1e-12]).all()
    chart = ca["chart"]
    assert chart.shape == (2 * out.n_edges, len(src.face_sizes))
    np.testing.assert_allclose(chart.sum(axis=1), 1.0, atol=1e-12)
    assert ((np.abs(chart) < 1e-12) | (np.abs(chart - 1) < 1e-12)).all(), "a corner mixed two faces' values"
    # the input is untouched
    np.testing.assert_array_equal(first.corner_attributes["uv"], uv)


@pytest.mark.parametrize("name", sorted(set(NAMES) - {"sqrt3", "dual"}))  # those have no face-born faces
def test_face_born_corners_keep_their_parent_face(name):
    """A child face of input face f reads f's values only: its chart is f (level 1)."""
    m, uv = uv_cube()
    out, c = run(m.with_attributes(corner={"chart": one_hot(m)}), name, correspondence=True)
    chart = out.corner_attributes["chart"].argmax(axis=1)
    of_face = np.repeat(c.face_kinds == 2, out.face_sizes)
    parent = np.repeat(c.face_parents, out.face_sizes)
    assert of_face.any()
    np.testing.assert_array_equal(chart[of_face], parent[of_face])


@pytest.mark.parametrize("iterations", [1, 2])
@pytest.mark.parametrize("name", NAMES)
def test_seamless_corner_data_equals_vertex_interpolation(name, iterations):
    """Data with one value per vertex, given per corner, comes out as the vertex attribute does
    (S @ a, with the scheme's own weights) wherever the scheme's rows lie in one face."""
    m = tm.Mesh.from_polygons(F.uv_cube().vertices, F.uv_cube().faces)
    a = np.column_stack([m.vertices[:, 0] ** 2 + m.vertices[:, 1], m.vertices[:, 2] * 3 - 1])
    src = m.with_attributes(vertex={"a": a}, corner={"a": a[m.face_indices]})
    out, c = run(src, name, iterations, correspondence=True)
    want = out.vertex_attributes["a"][out.face_indices]
    got = out.corner_attributes["a"]
    if SCHEMES[name][1]:
        np.testing.assert_allclose(got, want, atol=1e-12)
    else:
        # sqrt3: the face points (the mean of their face) agree, the smoothed old vertices are
        # read linearly, keeping their input value
        born = c.vertex_kinds[out.face_indices]
        if iterations == 1:  # (the next level's face points mean those linear values)
            np.testing.assert_allclose(got[born == 2], want[born == 2], atol=1e-12)
            old = born == 0
            np.testing.assert_allclose(got[old], a[c.vertex_origins[out.face_indices[old]]], atol=1e-12)
            assert not np.allclose(got[old], want[old])


@pytest.mark.parametrize("name", ["midpoint", "sierpinski", "menger"])
def test_input_vertex_corners_keep_their_face_value(name):
    """Where an output vertex is an input vertex, a corner of it in a child of face f has f's
    value there, whatever the other faces at that vertex hold."""
    m, uv = uv_cube()
    out, c = run(m.with_attributes(corner={"uv": uv}), name, correspondence=True)
    got = out.corner_attributes["uv"]
    starts = np.concatenate([[0], np.cumsum(m.face_sizes)[:-1]])
    checked = 0
    for g, (s, n) in enumerate(zip(np.concatenate([[0], np.cumsum(out.face_sizes)[:-1]]), out.face_sizes)):
        if c.face_kinds[g] != 2:
            continue
        f = c.face_parents[g]
        fv = m.face_indices[starts[f] : starts[f] + m.face_sizes[f]]
        for j in range(n):
            v = out.face_indices[s + j]
            if c.vertex_kinds[v] == 0:
                (k,) = np.flatnonzero(fv == c.vertex_origins[v])
                np.testing.assert_allclose(got[s + j], uv[starts[f] + k], atol=1e-12)
                checked += 1
    assert checked >= 24


@pytest.mark.parametrize("name", ["doo_sabin", "sqrt3", "simplest", "midpoint", "dual", "honeycomb", "vertex_truncation"])
@pytest.mark.parametrize("shape", ["disk", "annulus", "quad_grid"])
def test_open_meshes_carry_corner_data(name, shape):
    """Open input (boundary rules, faces that straddle the boundary): every output corner still
    takes one input face's values."""
    m = open_meshes.mesh(shape)
    src = m.with_attributes(corner={"chart": one_hot(m), "uv": m.vertices[m.face_indices][:, :2]})
    out = run(src, name, 1)
    chart = out.corner_attributes["chart"]
    assert chart.shape == (len(out.face_indices), len(m.face_sizes))
    assert ((np.abs(chart) < 1e-12) | (np.abs(chart - 1) < 1e-12)).all()
    np.testing.assert_allclose(chart.sum(axis=1), 1.0, atol=1e-12)
    # seamless UVs (the xy positions): linear schemes give the same as the vertex data
    v = src.with_attributes(vertex={"xy": m.vertices[:, :2]})
    o2 = run(v, name, 1)
    if SCHEMES[name][1]:
        np.testing.assert_allclose(o2.corner_attributes["uv"], o2.vertex_attributes["xy"][o2.face_indices], atol=1e-12)


def test_degenerate_inputs_carry_corner_data():
    """Sierpinski's output (self-loops, faces through a vertex twice) through the other schemes."""
    m, uv = uv_cube()
    s = m.with_attributes(corner={"uv": uv}).sierpinski(1)
    s = s.with_attributes(corner={"chart": one_hot(s)})
    for name in ("doo_sabin", "midpoint", "dual", "simplest", "honeycomb", "vertex_truncation", "sierpinski"):
        out = run(s, name, 1)
        ch = out.corner_attributes["chart"]
        assert ch.shape[0] == len(out.face_indices)
        assert ((np.abs(ch) < 1e-12) | (np.abs(ch - 1) < 1e-12)).all(), name


@pytest.mark.parametrize("name", sorted(set(NAMES) - {"menger"}))
def test_one_call_of_three_levels_equals_three_calls(name):
    """On closed input the corner data goes through the schemes' direct paths
    (src/schemes/corner_direct/), which Sierpinski declines from its second level on (self-loops):
    three levels in one call give the same corner rows as three calls of one level."""
    m, uv = uv_cube()
    src = m.with_attributes(corner={"uv": uv, "chart": one_hot(m)})
    once = run(src, name, 3 if name != "sierpinski" else 2)
    step = src
    for _ in range(3 if name != "sierpinski" else 2):
        step = run(step, name, 1)
    np.testing.assert_array_equal(once.face_indices, step.face_indices)
    for key in ("uv", "chart"):
        np.testing.assert_allclose(once.corner_attributes[key], step.corner_attributes[key], atol=1e-12)


def test_loop_all_on_quads_is_bilinear_in_every_face():
    """Loop fans a quad around its centroid; with corner_interpolation="all" the data is linear on
    that fan: corner data equal to the corner's position comes out as the positions of the
    midpoint refinement of the fan (stellate = the centroid fan, the same points)."""
    m = tm.cube()
    out = m.with_attributes(corner={"p": m.vertices[m.face_indices]}).loop(1)
    lin = m.stellate().midpoint(1)
    got = out.corner_attributes["p"]
    assert got.shape == (len(out.face_indices), 3)
    # every corner value is a point of the linear refinement (a vertex of stellate + midpoint)
    d = np.linalg.norm(got[:, None, :] - lin.vertices[None, :, :], axis=2).min(axis=1)
    assert d.max() < 1e-12
    # and an old vertex's corners keep the vertex itself
    old = out.face_indices < m.n_vertices
    np.testing.assert_allclose(got[old], m.vertices[out.face_indices[old]], atol=1e-12)


def test_zero_iterations_and_plain_calls_are_unchanged():
    m, uv = uv_cube()
    src = m.with_attributes(corner={"uv": uv})
    for name in NAMES:
        np.testing.assert_array_equal(run(src, name, 0).corner_attributes["uv"], uv)
        assert run(m, name, 1).corner_attributes == {}


@pytest.mark.parametrize("shape", ["disk", "annulus", "quad_grid"])
def test_loop_limit_normals_are_exact_at_boundaries(shape):
    """Loop's limit normals at boundary (crease) vertices do not change when the mesh is refined
    first: the cross tangent is an eigenvector of the plain boundary rules (src/schemes/limit.rs)."""
    m = open_meshes.mesh(shape)
    p0, n0 = m.limit_points("loop")
    p1, n1 = m.loop(1).limit_points("loop")
    v = m.n_vertices
    np.testing.assert_allclose(p1[:v], p0, atol=1e-10)
    assert (np.einsum("ij,ij->i", n0, n1[:v]) > 1 - 1e-9).all()
