"""topomesh against OpenSubdiv itself (issue 15, part 6), through the test-only reference in
tests/osd: Blender's bpy (Catmull-Clark, creases, boundary and face-varying options) and, when
built, the opensubdiv-petite binary (Loop, Chaikin).

Two kinds of tests: comparisons of topomesh's output with OpenSubdiv's up to vertex order
(1e-6 of the bounding-box diagonal: the reference computes in float32), and checks that the
reference follows the published rules on the fixtures, so that a mismatch later can be blamed
on the right side (the harness's option mapping is part of what they test).
"""

from __future__ import annotations

import numpy as np
import pytest

import topomesh
from tests.osd import assert_same_mesh, available, match_faces, match_points, refine_many, request
from tests.osd import fixtures as F
from tests.osd import rules as Ru
from tests.osd import petite_ref

# Blender's tests skip through the `ref` fixture, so that petite's run without bpy
REASON = available()
PETITE = petite_ref.available()
needs_petite = pytest.mark.skipif(PETITE is not None, reason=PETITE or "")

RTOL = 1e-6


def closed_meshes() -> dict[str, topomesh.Mesh]:
    mixed = F.mixed_closed()
    return {
        "cube": topomesh.cube(),
        "torus_8_6": topomesh.torus(8, 6),
        "mixed_closed": topomesh.Mesh.from_polygons(mixed.vertices, mixed.faces),
        "genus_2": topomesh.genus_surface(2),
    }


LEVELS = (1, 2, 3)
QUIRK_EDGES = {(0, 1): 2.0, (0, 5): 2.0}  # both edges of the open grid's corner 0


def _requests() -> dict[tuple, dict]:
    reqs: dict[tuple, dict] = {}
    for name, m in closed_meshes().items():
        for lv in LEVELS:
            reqs[("closed", name, lv)] = request(m.vertices, (m.face_sizes, m.face_indices), lv)
    for name in ("creased_cube", "corner_cube"):
        fx = F.ALL[name]
        for lv in LEVELS:
            reqs[(name, lv)] = request(fx.vertices, fx.faces, lv, **fx.options)
    for name in ("quad_grid", "cylinder"):
        fx = F.ALL[name]
        for mode in ("edge_only", "edge_and_corner"):
            for lv in (1, 2):
                reqs[(name, mode, lv)] = request(fx.vertices, fx.faces, lv, boundary=mode)
    uv = F.uv_cube()
    for mode in ("all", "corners_only", "none"):
        reqs[("uv_cube", mode)] = request(uv.vertices, uv.faces, 1, uvs=uv.options["uvs"], uv_interpolation=mode)
    # Blender's valence-2 quirk, sent to Blender on purpose (request() would route it to petite)
    quirk = request(F.quad_grid().vertices, F.quad_grid().faces, 1, boundary="edge_only",
                    edge_sharpness=QUIRK_EDGES, backend="petite")
    reqs[("quirk",)] = {**quirk, "backend": np.str_("blender")}
    grid = F.uv_grid()
    for mode, boundary in (("all", "edge_and_corner"), ("boundaries", "edge_and_corner"),
                           ("none", "edge_and_corner"), ("none", "edge_only")):
        reqs[("uv_grid", mode, boundary)] = request(grid.vertices, grid.faces, 1, boundary=boundary,
                                                    uvs=grid.options["uvs"], uv_interpolation=mode)
    return reqs


@pytest.fixture(scope="module")
def ref():
    """Every Blender request of this module, run in one subprocess."""
    if REASON is not None:
        pytest.skip(REASON)
    reqs = _requests()
    return dict(zip(reqs, refine_many(list(reqs.values()))))


# --------------------------------------------------------------------------- topomesh == OpenSubdiv


@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("name", list(closed_meshes()))
def test_closed_catmull_clark_equals_opensubdiv(ref, name, level):
    mesh = closed_meshes()[name]
    ours = mesh.catmull_clark(level)
    theirs = ref[("closed", name, level)]
    assert ours.n_faces == len(theirs.face_sizes)
    vmap = match_points(ours.vertices, theirs.positions, RTOL)
    # same connectivity too: every face of ours has a reference face on the same vertices
    fmap = match_faces((ours.face_sizes, ours.face_indices), (theirs.face_sizes, theirs.face_indices), vmap)
    assert len(np.unique(fmap)) == ours.n_faces


def test_matching_helpers_catch_differences(ref):
    """The comparison fails when it should: a moved vertex, a wrong UV, another level."""
    mesh = topomesh.cube()
    ours, theirs = mesh.catmull_clark(1), ref[("closed", "cube", 1)]
    faces = (ours.face_sizes, ours.face_indices)
    assert_same_mesh(ours.vertices, faces, theirs)
    moved = ours.vertices.copy()
    moved[5] += 1e-4
    with pytest.raises(AssertionError, match="our point 5"):
        assert_same_mesh(moved, faces, theirs)
    with pytest.raises(AssertionError, match="point counts differ"):
        match_points(mesh.catmull_clark(2).vertices, theirs.positions)
    uv = F.uv_cube()
    out = ref[("uv_cube", "all")]
    assert_same_mesh(out.positions, (out.face_sizes, out.face_indices), out, out.uvs)  # itself, any order
    perm = np.random.default_rng(1).permutation(len(out.positions))
    inv = np.argsort(perm)
    assert_same_mesh(out.positions[perm], (out.face_sizes, inv[out.face_indices]), out, out.uvs)
    wrong = out.uvs.copy()
    wrong[7] += [0.01, 0]
    with pytest.raises(AssertionError, match="our corner 7"):
        assert_same_mesh(out.positions, (out.face_sizes, out.face_indices), out, wrong)
    assert uv.corner_count == len(uv.options["uvs"]) == len(uv.uv_index) and len(uv.uv_table) == 14
    assert np.array_equal(uv.uv_table[uv.uv_index], uv.options["uvs"])


# --------------------------------------------------------------------------- the reference itself


def test_reference_sharp_and_semi_sharp_edges_level_1(ref):
    """Level 1 of the creased cube: the edges of sharpness inf and 1.5 get their midpoints, the
    edge of sharpness 0.4 gets 0.4 of the way from the smooth point to the midpoint (this pins
    Blender's crease -> sharpness mapping s = 10 c^2), an ordinary edge the smooth point."""
    fx = F.creased_cube()
    out = ref[("creased_cube", 1)].positions
    tol = RTOL * Ru.scale(out)
    for edge, s in ((F.SHARP_EDGE, 1.0), (F.SEMI_EDGE, 1.0), (F.FRACTIONAL_EDGE, 0.4), ((0, 1), 0.0)):
        expected = Ru.edge_point(fx.vertices, fx.faces, *edge, s)
        assert Ru.nearest(out, expected)[1] < tol, edge
        # and not the other rules: the fixture tells them apart
        for other in {0.0, 0.4, 1.0} - {s}:
            assert Ru.nearest(out, Ru.edge_point(fx.vertices, fx.faces, *edge, other))[1] > 100 * tol


def test_reference_semi_sharpness_decreases_by_one_per_level(ref):
    """Level 2: the children of the 1.5 edge have sharpness 0.5 (half-way blend), the children of
    the infinitely sharp edge stay sharp (midpoints)."""
    fx = F.creased_cube()
    r1, r2 = ref[("creased_cube", 1)], ref[("creased_cube", 2)]
    p1, f1 = r1.positions, r1.faces
    tol = RTOL * Ru.scale(p1)
    face_points = Ru.centroids(fx.vertices, fx.faces)
    for edge, child_s in ((F.SEMI_EDGE, 0.5), (F.SHARP_EDGE, 1.0)):
        e, d = Ru.nearest(p1, fx.vertices[list(edge)].mean(axis=0))
        assert d < tol
        ends = [u for u in Ru.neighbours(f1, e) if np.linalg.norm(face_points - p1[u], axis=1).min() > tol]
        assert len(ends) == 2  # the children of the edge's two end vertices
        for u in ends:
            assert Ru.nearest(r2.positions, Ru.edge_point(p1, f1, e, u, child_s))[1] < tol, (edge, u)
            if child_s < 1:
                assert Ru.nearest(r2.positions, Ru.edge_point(p1, f1, e, u, 1.0))[1] > 100 * tol


def test_reference_corner_vertex_sharpness_two(ref):
    """Vertex sharpness 2: the vertex stays put at levels 1 and 2 (corner rule), and its level-3
    point is the smooth rule applied to level 2."""
    fx = F.corner_cube()
    v = fx.vertices[F.CORNER_VERTEX]
    r1, r2, r3 = (ref[("corner_cube", lv)] for lv in LEVELS)
    tol = RTOL * Ru.scale(r1.positions)
    assert Ru.nearest(r1.positions, v)[1] == 0.0
    assert Ru.nearest(r2.positions, v)[1] == 0.0
    assert Ru.nearest(r3.positions, v)[1] > 0.1
    i = Ru.nearest(r2.positions, v)[0]
    smooth = Ru.smooth_vertex_point(r2.positions, r2.faces, i)
    assert Ru.nearest(r3.positions, smooth)[1] < tol


@pytest.mark.parametrize("mode", ["edge_only", "edge_and_corner"])
def test_reference_open_grid_boundary(ref, mode):
    """Open grid, level 1: boundary edge points are midpoints, boundary vertices follow the curve
    rule (a + 6 v + b) / 8; the valence-2 corners stay put with edge_and_corner and follow the
    curve rule with edge_only; interior vertices the smooth rule."""
    fx = F.quad_grid()
    out = ref[("quad_grid", mode, 1)]
    p = out.positions
    tol = RTOL * Ru.scale(p)
    bnd = Ru.boundary_edges(fx.faces)
    assert len(bnd) == 16
    for a, b in bnd:
        assert Ru.nearest(p, (fx.vertices[a] + fx.vertices[b]) / 2)[1] < tol
    corners = F.grid_corners()
    on_boundary = {v for e in bnd for v in e}
    for v in range(len(fx.vertices)):
        nb = Ru.neighbours(fx.faces, v)
        if v in on_boundary:
            a, b = [u for u in nb if u in on_boundary and ((min(u, v), max(u, v)) in bnd)]
            curve = Ru.crease_vertex_point(fx.vertices, a, v, b)
            expected = fx.vertices[v] if (v in corners and mode == "edge_and_corner") else curve
            assert Ru.nearest(p, expected)[1] < tol, v
            if v in corners:  # the two modes really differ there
                assert np.linalg.norm(curve - fx.vertices[v]) > 1e3 * tol
        else:
            assert Ru.nearest(p, Ru.smooth_vertex_point(fx.vertices, fx.faces, v))[1] < tol, v
    assert len(out.face_sizes) == 4 * len(fx.faces) and set(out.face_sizes.tolist()) == {4}


def test_reference_cylinder_has_no_corners(ref):
    """Open cylinder: no valence-2 vertex, so both boundary modes give the same surface; the
    boundary loops follow the curve rule."""
    fx = F.cylinder()
    for lv in (1, 2):
        a, b = ref[("cylinder", "edge_only", lv)], ref[("cylinder", "edge_and_corner", lv)]
        match_points(a.positions, b.positions, RTOL)
        assert len(a.face_sizes) == len(fx.faces) * 4**lv
    p = ref[("cylinder", "edge_only", 1)].positions
    tol = RTOL * Ru.scale(p)
    n = 8
    for ring in (0, 3):
        for k in range(n):
            v, a, b = ring * n + k, ring * n + (k - 1) % n, ring * n + (k + 1) % n
            assert Ru.nearest(p, Ru.crease_vertex_point(fx.vertices, a, v, b))[1] < tol


def _uv_corner_table(fx, out):
    """For each reference corner at a level-1 vertex point: (input face, input vertex, uv)."""
    face_points = Ru.centroids(fx.vertices, fx.faces)
    tol = RTOL * Ru.scale(out.positions)
    starts = np.concatenate([[0], np.cumsum(out.face_sizes)[:-1]])
    rows = []
    for s, n in zip(starts, out.face_sizes):
        vs = out.face_indices[s : s + n]
        d = [np.linalg.norm(face_points - out.positions[v], axis=1) for v in vs]
        k = [j for j in range(n) if d[j].min() < tol]
        assert len(k) == 1  # each child quad has one face point
        f = int(np.argmin(d[k[0]]))
        opposite = (k[0] + 2) % n  # a child quad's vertex point is opposite its face point
        fv = fx.faces[f]
        v = min(fv, key=lambda w: np.linalg.norm(fx.vertices[w] - out.positions[vs[opposite]]))
        rows.append((f, v, out.uvs[s + opposite], out.uvs[s + k[0]]))
    return rows


def test_reference_uv_linear_all_is_bilinear(ref):
    """uv_interpolation 'all' (FVAR_LINEAR_ALL): a child corner at an input vertex keeps its
    face's UV there, the face point gets the mean of the face's UVs; 24 child faces, 96 corners."""
    fx = F.uv_cube()
    uvs = fx.options["uvs"].reshape(6, 4, 2)
    out = ref[("uv_cube", "all")]
    assert out.uvs.shape == (96, 2)
    for f, v, uv_v, uv_f in _uv_corner_table(fx, out):
        assert np.allclose(uv_v, uvs[f][fx.faces[f].index(v)], atol=1e-6)
        assert np.allclose(uv_f, uvs[f].mean(axis=0), atol=1e-6)


def test_reference_uv_corners_only_and_smooth(ref):
    """The cross's outer UV corners (a UV value used by one face only): 'corners_only' keeps
    them, 'none' (smooth everywhere) moves them along the UV boundary curve (a + 6 v + b) / 8."""
    fx = F.uv_cube()
    uvs = fx.options["uvs"].reshape(6, 4, 2)
    flat = fx.options["uvs"]
    values, counts = np.unique(flat.round(9), axis=0, return_counts=True)
    lonely = {tuple(u) for u, c in zip(values, counts) if c == 1}
    assert len(lonely) == 8  # the eight outer corners of the cross
    checked = 0
    for mode in ("corners_only", "none"):
        for f, v, uv_v, _ in _uv_corner_table(fx, ref[("uv_cube", mode)]):
            j = fx.faces[f].index(v)
            if tuple(uvs[f][j].round(9)) not in lonely:
                continue
            curve = (uvs[f][j - 1] + 6 * uvs[f][j] + uvs[f][(j + 1) % 4]) / 8
            expected = uvs[f][j] if mode == "corners_only" else curve
            assert np.allclose(uv_v, expected, atol=1e-6), (mode, f, v)
            checked += 1
    assert checked == 16


@pytest.mark.parametrize(("mode", "boundary"), [("all", "edge_and_corner"), ("boundaries", "edge_and_corner"),
                                              ("none", "edge_and_corner"), ("none", "edge_only")])
def test_reference_uv_grid_interpolation(ref, mode, boundary):
    """One UV chart u = x^2, v = y on the open grid (level 1, vertex-point corners): 'all' keeps
    every UV; 'boundaries' keeps the boundary UVs and smooths the interior ones with the
    Catmull-Clark vertex rule (applied to the UVs); 'none' smooths both, the boundary ones along
    the UV boundary curve (a + 6 v + b) / 8, except at the mesh's corners when the vertex
    boundary interpolation pins them (edge_and_corner): face-varying data is smooth only where
    the mesh is."""
    fx = F.uv_grid()
    table = np.column_stack([fx.vertices[:, 0] ** 2, fx.vertices[:, 1]])
    bnd = set(Ru.boundary_edges(fx.faces))
    on_boundary = {w for e in bnd for w in e}
    pinned = set(F.grid_corners()) if boundary == "edge_and_corner" else set()
    rows = _uv_corner_table(fx, ref[("uv_grid", mode, boundary)])
    assert len(rows) == 4 * len(fx.faces)
    moved = 0
    for f, v, uv_v, _ in rows:
        if v in on_boundary:
            a, b = [u for u in Ru.neighbours(fx.faces, v) if (min(u, v), max(u, v)) in bnd]
            curve = mode == "none" and v not in pinned
            expected = Ru.crease_vertex_point(table, a, v, b) if curve else table[v]
        else:
            expected = table[v] if mode == "all" else Ru.smooth_vertex_point(table, fx.faces, v)
        assert np.allclose(uv_v, expected, atol=1e-6), (mode, f, v)
        moved += not np.allclose(expected, table[v], atol=1e-4)
    assert (moved > 0) == (mode != "all")


def test_blender_valence_two_quirk_is_avoided(ref):
    """Blender adds the smaller sharpness of a two-edge vertex's edges to the vertex (so corner 0
    of the grid stays put with both its edges creased, even with edge_only); OpenSubdiv does not.
    request() therefore refuses such a mesh for Blender and routes it to petite by default."""
    g = F.quad_grid()
    assert Ru.nearest(ref[("quirk",)].positions, g.vertices[0])[1] == 0.0
    with pytest.raises(ValueError, match="vertex 0 has two edges"):
        request(g.vertices, g.faces, 1, edge_sharpness=QUIRK_EDGES, backend="blender")
    assert str(request(g.vertices, g.faces, 1, edge_sharpness=QUIRK_EDGES)["backend"]) == "petite"
    if PETITE is None:
        (pure,) = refine_many([request(g.vertices, g.faces, 1, boundary="edge_only", edge_sharpness=QUIRK_EDGES)])
        a, b = 1, 5
        assert Ru.nearest(pure.positions, Ru.crease_vertex_point(g.vertices, a, 0, b))[1] < RTOL * Ru.scale(g.vertices)


# --------------------------------------------------------------------------- opensubdiv-petite



@needs_petite
def test_petite_agrees_with_blender(ref):
    """Two OpenSubdiv front-ends, one answer: petite (sharpness passed through) and Blender
    (sharpness as a crease c with s = 10 c^2) on the creased cube and the open grid."""
    fx, grid = F.creased_cube(), F.quad_grid()
    reqs = [request(fx.vertices, fx.faces, lv, backend="petite", **fx.options) for lv in LEVELS]
    reqs += [request(grid.vertices, grid.faces, 2, boundary=m, backend="petite") for m in ("edge_only", "edge_and_corner")]
    got = refine_many(reqs)
    for lv, g in zip(LEVELS, got):
        match_points(g.positions, ref[("creased_cube", lv)].positions, RTOL)
    for m, g in zip(("edge_only", "edge_and_corner"), got[3:]):
        match_points(g.positions, ref[("quad_grid", m, 2)].positions, RTOL)


@needs_petite
@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("name", ["tetrahedron", "octahedron", "icosahedron"])
def test_closed_loop_equals_opensubdiv(name, level):
    mesh = getattr(topomesh, name)()
    (theirs,) = refine_many([request(mesh.vertices, (mesh.face_sizes, mesh.face_indices), level, scheme="loop")])
    ours = mesh.loop(level)
    vmap = match_points(ours.vertices, theirs.positions, RTOL)
    match_faces((ours.face_sizes, ours.face_indices), (theirs.face_sizes, theirs.face_indices), vmap)


@needs_petite
def test_petite_chaikin_differs_from_uniform_only_where_sharpness_varies():
    """Chaikin's crease method changes child sharpness only where sharp edges of different
    sharpness meet: on a cube whose top face edges have sharpness 1, 2, 3, 2 the two methods
    differ at level 2, and on a cube with one uniform-sharpness crease loop they agree."""
    v, f = F.CUBE_V, F.CUBE_F
    loop_edges = [(4, 5), (5, 7), (7, 6), (6, 4)]
    varying = dict(zip(loop_edges, (1.0, 2.0, 3.0, 2.0)))
    uniform = dict.fromkeys(loop_edges, 2.0)
    outs = refine_many([request(v, f, 2, edge_sharpness=s, crease_method=c, backend="petite")
                        for s in (varying, uniform) for c in ("uniform", "chaikin")])
    assert not np.allclose(outs[0].positions, outs[1].positions, atol=1e-5)
    match_points(outs[2].positions, outs[3].positions, RTOL)


@pytest.fixture(scope="module")
def loop_ref():
    """The Loop requests of this module (petite), in one subprocess."""
    grid, creased, corner = (F.triangulated(F.ALL[n]) for n in ("quad_grid", "creased_cube", "corner_cube"))
    reqs = {(grid.name, m): request(grid.vertices, grid.faces, 1, scheme="loop", boundary=m)
            for m in ("edge_only", "edge_and_corner")}
    reqs[(creased.name, 1)] = request(creased.vertices, creased.faces, 1, scheme="loop", **creased.options)
    for lv in LEVELS:
        reqs[(corner.name, lv)] = request(corner.vertices, corner.faces, lv, scheme="loop", **corner.options)
    return dict(zip(reqs, refine_many(list(reqs.values()))))


@needs_petite
@pytest.mark.parametrize("mode", ["edge_only", "edge_and_corner"])
def test_petite_loop_open_grid_boundary(loop_ref, mode):
    """Loop on the triangulated open grid, level 1: boundary edges get midpoints, interior edges
    3/8 3/8 1/8 1/8, interior vertices Loop's beta rule, boundary vertices the curve rule, except
    that edge_and_corner pins the two corners that lie in a single triangle."""
    fx = F.triangulated(F.quad_grid())
    out = loop_ref[(fx.name, mode)]
    p, v = out.positions, fx.vertices
    tol = RTOL * Ru.scale(p)
    assert len(out.face_sizes) == 4 * len(fx.faces) and set(out.face_sizes.tolist()) == {3}
    bnd = set(Ru.boundary_edges(fx.faces))
    for a, b in Ru.edge_faces(fx.faces):
        expected = (v[a] + v[b]) / 2 if (a, b) in bnd else Ru.loop_edge_point(v, fx.faces, a, b)
        assert Ru.nearest(p, expected)[1] < tol, (a, b)
    on_boundary = {w for e in bnd for w in e}
    single = {w for w in on_boundary if sum(w in f for f in fx.faces) == 1}
    assert single == {4, 20}
    for w in range(len(v)):
        if w in on_boundary:
            a, b = [u for u in Ru.neighbours(fx.faces, w) if (min(u, w), max(u, w)) in bnd]
            pinned = w in single and mode == "edge_and_corner"
            expected = v[w] if pinned else Ru.crease_vertex_point(v, a, w, b)
        else:
            expected = Ru.loop_vertex_point(v, fx.faces, w)
        assert Ru.nearest(p, expected)[1] < tol, w


@needs_petite
def test_petite_loop_creases_and_corner(loop_ref):
    """Loop on the triangulated creased cube (level 1): the inf and 1.5 edges get midpoints, the
    0.4 edge 0.4 of the way from Loop's edge point; on the corner cube the sharpness-2 vertex
    stays for two levels and moves at the third."""
    fx = F.triangulated(F.creased_cube())
    p = loop_ref[(fx.name, 1)].positions
    tol = RTOL * Ru.scale(p)
    for edge, s in ((F.SHARP_EDGE, 1.0), (F.SEMI_EDGE, 1.0), (F.FRACTIONAL_EDGE, 0.4)):
        assert Ru.nearest(p, Ru.loop_edge_point(fx.vertices, fx.faces, *edge, s))[1] < tol, edge
        assert Ru.nearest(p, Ru.loop_edge_point(fx.vertices, fx.faces, *edge, 0.0))[1] > 100 * tol
    corner = F.triangulated(F.corner_cube())
    v = corner.vertices[F.CORNER_VERTEX]
    d = [Ru.nearest(loop_ref[(corner.name, lv)].positions, v)[1] for lv in LEVELS]
    assert d[0] == 0.0 and d[1] == 0.0 and d[2] > 0.05


# --------------------------------------------------------------------------- topomesh's open meshes,
# creases and face-varying data == OpenSubdiv


def ours(fx, **extra) -> topomesh.Mesh:
    """The fixture as a topomesh Mesh with its sharpness and UVs (OpenSubdiv units)."""
    m = topomesh.Mesh.from_polygons(fx.vertices, fx.faces, close_boundaries=True)
    o = {**fx.options, **extra}
    if "edge_sharpness" in o or "vertex_sharpness" in o:
        m = m.with_creases(o.get("edge_sharpness"), o.get("vertex_sharpness"))
    if "uvs" in o:
        m = m.with_attributes(corner={"uv": o["uvs"]})
    return m


@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("name", ["creased_cube", "corner_cube"])
def test_creases_equal_opensubdiv(ref, name, level):
    out = ours(F.ALL[name]).catmull_clark(level)
    assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), ref[(name, level)])


@pytest.mark.parametrize("level", (1, 2))
@pytest.mark.parametrize("mode", ["edge_only", "edge_and_corner"])
@pytest.mark.parametrize("name", ["quad_grid", "cylinder"])
def test_open_meshes_equal_opensubdiv(ref, name, mode, level):
    out = ours(F.ALL[name]).catmull_clark(level, boundary=mode)
    assert out.n_boundary_loops == (1 if name == "quad_grid" else 2) if hasattr(out, "n_boundary_loops") else out.n_holes
    assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), ref[(name, mode, level)])


# OpenSubdiv's face-varying choices as topomesh names them (Blender's 'none' is FVAR_LINEAR_NONE)
FVAR = {"all": "all", "corners_only": "corners_only", "none": "smooth", "boundaries": "boundaries"}


@pytest.mark.parametrize("mode", ["all", "corners_only", "none"])
def test_uv_cube_seams_equal_opensubdiv(ref, mode):
    fx = F.uv_cube()
    out = ours(fx).catmull_clark(1, corner_interpolation=FVAR[mode])
    assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), ref[("uv_cube", mode)], out.corner_attributes["uv"])


@pytest.mark.parametrize(("mode", "boundary"), [("all", "edge_and_corner"), ("boundaries", "edge_and_corner"),
                                              ("none", "edge_and_corner"), ("none", "edge_only")])
def test_uv_grid_equals_opensubdiv(ref, mode, boundary):
    fx = F.uv_grid()
    out = ours(fx).catmull_clark(1, boundary=boundary, corner_interpolation=FVAR[mode])
    assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), ref[("uv_grid", mode, boundary)], out.corner_attributes["uv"])


def test_uv_table_and_index_equal_per_corner_uvs():
    fx = F.uv_cube()
    m = topomesh.Mesh.from_polygons(fx.vertices, fx.faces)
    a = m.with_attributes(corner={"uv": (fx.uv_table, fx.uv_index)}).catmull_clark(2, corner_interpolation="smooth")
    b = m.with_attributes(corner={"uv": fx.options["uvs"]}).catmull_clark(2, corner_interpolation="smooth")
    np.testing.assert_array_equal(a.corner_attributes["uv"], b.corner_attributes["uv"])


@needs_petite
@pytest.mark.parametrize("mode", ["edge_only", "edge_and_corner"])
def test_loop_open_grid_equals_opensubdiv(loop_ref, mode):
    fx = F.triangulated(F.quad_grid())
    out = ours(fx).loop(1, boundary=mode)
    assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), loop_ref[(fx.name, mode)])


@needs_petite
def test_loop_creases_equal_opensubdiv(loop_ref):
    creased, corner = F.triangulated(F.creased_cube()), F.triangulated(F.corner_cube())
    out = ours(creased).loop(1)
    assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), loop_ref[(creased.name, 1)])
    for lv in LEVELS:
        out = ours(corner).loop(lv)
        assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), loop_ref[(corner.name, lv)])


@needs_petite
@pytest.mark.parametrize("method", ["uniform", "chaikin"])
@pytest.mark.parametrize("scheme", ["catmull_clark", "loop"])
def test_chaikin_equals_opensubdiv(scheme, method):
    """Sharp edges of different sharpness meeting (Chaikin averages them), levels 1-3."""
    fx = F.creased_cube() if scheme == "catmull_clark" else F.triangulated(F.creased_cube())
    loop_edges = [(4, 5), (5, 7), (7, 6), (6, 4)]
    s = dict(zip(loop_edges, (1.0, 2.5, 3.0, 0.5)))
    m = topomesh.Mesh.from_polygons(fx.vertices, fx.faces).with_creases(s)
    got = refine_many([request(fx.vertices, fx.faces, lv, scheme=scheme, edge_sharpness=s, crease_method=method, backend="petite") for lv in LEVELS])
    for lv, theirs in zip(LEVELS, got):
        out = getattr(m, scheme)(lv, crease_method=method)
        assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), theirs)
