"""TopMod tools of issue 16: object tools, wireframe, multi-face handle,
rind by scaling, pinch, conical cuts and convex hulls."""

import warnings

import numpy as np
import pytest

import topomesh
from topomesh import MeshError

trimesh = pytest.importorskip("trimesh")


def counts(m):
    m.validate()
    return (m.n_vertices, m.n_edges, m.n_faces, m.genus)


def check_watertight(m, genus):
    t = m.to_trimesh()
    assert t.is_watertight
    assert (2 - t.euler_number) // 2 == genus


SHAPES = [topomesh.cube, topomesh.dodecahedron, topomesh.tetrahedron, topomesh.octahedron, topomesh.icosahedron]


@pytest.mark.parametrize("make", SHAPES + [lambda: topomesh.torus(6, 4), lambda: topomesh.genus_surface(3)])
def test_wireframe_genus_formula(make):
    m = make()
    v, e, f, g = counts(m)
    w = m.wireframe(0.05)
    assert counts(w) == (4 * e, 10 * e, 2 * v + 4 * e, e - v + 1)
    assert e - v + 1 == 2 * g + f - 1
    w2 = m.wireframe(0.05, width=0.02)
    assert counts(w2) == counts(w)
    if m.n_components == 1 and make in SHAPES:
        check_watertight(w, e - v + 1)
        assert len(w.self_intersections()) == 0


def test_crossing_report_stops_counting_at_a_million():
    # a wireframe far thicker than its edges folds every tube through its
    # neighbours: 88 M crossing pairs for P8000 (28 s to count them all);
    # the warning counts a million and says so, and the mesh is the same
    m = topomesh.conway("P2000")
    with pytest.warns(topomesh.GeometryWarning, match=r"at least 1000000 crossing triangle pairs"):
        w = m.wireframe(0.1)
    plain = m.wireframe(0.1, check_crossings=False)
    assert np.array_equal(w.vertices, plain.vertices)
    assert np.array_equal(w.face_indices, plain.face_indices)
    # below the limit the exact count is reported
    with pytest.warns(topomesh.GeometryWarning) as rec:
        topomesh.conway("P60").wireframe(0.5)
    msg = str(rec[0].message)
    assert "at least" not in msg and int(msg.split("surface: ")[1].split()[0]) > 2000


def column_counts(m, n):
    # the counts of docs/tools.md: V1, V2, V3 vertices of valence 1, 2, >= 3
    e, k = m.n_edges, n // 2
    vh = m.valence_histogram
    v1, v2 = vh.get(1, 0), vh.get(2, 0)
    v3 = sum(c for d, c in vh.items() if d >= 3)
    ev = 1 if n % 2 == 0 else 0
    s3 = 2 * e - v1 - 2 * v2  # valences summed over the valence >= 3 vertices (odd n: fan triangles)
    od = 1 - ev
    return (2 * n * e + od * v3, 3 * n * e + (k + 1) * (2 * e - v1) - (1 + ev) * v2 + 2 * od * s3,
            n * e + k * (2 * e - v1) + (1 + ev) * v3 + od * (v2 + 2 * s3) + v1)


@pytest.mark.parametrize("make", SHAPES + [lambda: topomesh.cube().subdivide_all_edges(1)])
@pytest.mark.parametrize("n", [3, 4, 7])
def test_wireframe_columns(make, n):
    m = make()
    v, e, f, g = counts(m)
    before = m.vertices.copy()
    c = m.wireframe_columns(0.05, n)
    assert counts(c)[:3] == column_counts(m, n)
    assert c.genus == e - v + 1 and c.n_components == 1
    check_watertight(c, e - v + 1)
    assert len(c.self_intersections()) == 0
    sizes = c.face_size_histogram
    vh = m.valence_histogram
    quads = n * e + (n // 2) * (2 * e - vh.get(1, 0)) + (n % 2) * vh.get(2, 0)
    assert sizes.get(4, 0) >= quads
    assert np.array_equal(m.vertices, before)


@pytest.mark.parametrize("make", [lambda: topomesh.torus(6, 4), lambda: topomesh.genus_surface(2)])
def test_wireframe_columns_curved(make):
    # at the coarse torus' saddle vertices (n = 3, 4, 5) and the genus
    # surface's valence-5 vertices (n = 8) the plain joints cross; the checked
    # call moves those vertices' rings out until they do not (docs/tools.md):
    # no GeometryWarning, no crossing, the same counts and connectivity
    m = make()
    v, e, f, g = counts(m)
    crossed = 0
    for n in (3, 4, 5, 8):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            c = m.wireframe_columns(0.05, n)
        plain = m.wireframe_columns(0.05, n, check_crossings=False)
        assert counts(c) == (*column_counts(m, n), e - v + 1)
        assert c.to_trimesh().is_watertight
        assert len(c.self_intersections()) == 0
        assert np.array_equal(c.face_indices, plain.face_indices) and np.array_equal(c.face_sizes, plain.face_sizes)
        crossed += len(plain.self_intersections()) > 0
    assert crossed >= 1  # the case is one the check had to mend


def test_wireframe_columns_open_mesh_joints_moved_out():
    # open meshes take the same check: the three-holed genus-2 patch's joints
    # cross at n = 8 (156 pairs) and are moved out; the holes take no part
    from tests.open_meshes import mesh

    m = mesh("genus2_three_holes")
    v, e = m.vertices.copy(), m.edges
    t = 0.1 * float(np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1).min())
    plain = m.wireframe_columns(t, 8, check_crossings=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        c = m.wireframe_columns(t, 8)
    assert len(plain.self_intersections()) > 0 and len(c.self_intersections()) == 0
    assert counts(c) == counts(plain) and np.array_equal(c.face_indices, plain.face_indices)
    assert np.array_equal(m.vertices, v)


@pytest.mark.parametrize("make", [lambda: topomesh.torus(24, 12), lambda: topomesh.genus_surface(2), lambda: topomesh.genus_surface(3)])
def test_wireframe_columns_quad_meshes_do_not_cross(make):
    # the joints between columns at right angles (every vertex of a quad
    # mesh) no longer fold over each other (ring margin 0.25 t, docs/tools.md):
    # no GeometryWarning with the default four sides, nor with 5 or 6; nor
    # with 3, whose bottom caps are fans (the torus' 8-gons crossed its strips)
    m = make()
    for n in (3, 4, 5, 6):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            c = m.wireframe_columns(0.05, n)
        assert len(c.self_intersections()) == 0, n


def test_wireframe_columns_errors():
    c = topomesh.cube()
    for kw, word in [(dict(thickness=0.0), "thickness"), (dict(segments=2), "segments"), (dict(segments=101), "segments"), (dict(thickness=1.5), "too short")]:
        with pytest.raises(MeshError, match=word):
            c.wireframe_columns(**kw)
    loop, _ = topomesh.cube().insert_edge(0, 0, 0, 0)
    with pytest.raises(MeshError, match="self-loop"):
        loop.wireframe_columns(0.05)
    assert counts(c.wireframe_columns()) == (96, 216, 112, 5)  # TopMod's defaults: thickness 0.25, 4 sides


def test_multi_face_handle_closest_edge():
    # two cubes with facing faces: four planar bridges, the tube of a pipe
    a, b = topomesh.cube(), topomesh.cube()
    two = topomesh.Mesh.from_polygons(np.r_[a.vertices, b.vertices + [3.0, 0, 0]], [list(f) for f in _faces(a)] + [list(np.array(f) + 8) for f in _faces(b)])
    sel = [_face_at(two, [1, 0, 0]), _face_at(two, [2, 0, 0])]
    r = two.multi_face_handle(sel, algorithm="closest_edge")
    assert counts(r) == (16, 28, 14, 0) and r.n_components == 1
    check_watertight(r, 0)
    with pytest.raises(MeshError, match="algorithm"):
        two.multi_face_handle(sel, algorithm="nearest")
    with pytest.raises(MeshError, match="twice"):
        two.multi_face_handle([sel[0], sel[0]], algorithm="closest_edge")


def _faces(m):
    off = np.r_[0, np.cumsum(m.face_sizes)]
    return [m.face_indices[off[i] : off[i + 1]] for i in range(m.n_faces)]


def test_wireframe_errors_and_input_untouched():
    m = topomesh.cube()
    before = m.vertices.copy()
    for bad in [0.0, -1.0, float("nan")]:
        with pytest.raises(MeshError, match="thickness"):
            m.wireframe(bad)
    with pytest.raises(MeshError, match="width"):
        m.wireframe(0.1, width=-1.0)
    assert np.array_equal(m.vertices, before)


def test_wireframe_tools_check_crossings_keyword():
    # the crossing report warns by default; check_crossings=False skips it and
    # changes nothing else (the report is most of the call on large inputs)
    cube, torus = topomesh.cube(), topomesh.torus(8, 3)
    for run, n_pairs in [
        (lambda **kw: cube.wireframe(1.5, **kw), 732),  # tubes deeper than the cube is wide
        (lambda **kw: torus.wireframe_columns(0.2, 4, **kw), 242),  # fat columns on a three-sided torus, no room to move them
    ]:
        with pytest.warns(topomesh.GeometryWarning, match=f" {n_pairs} crossing triangle pairs") as w:
            a = run()
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            b = run(check_crossings=False)
        assert len(b.self_intersections()) == n_pairs
        assert np.array_equal(a.vertices, b.vertices)
        assert np.array_equal(a.face_indices, b.face_indices)
        assert np.array_equal(a.face_sizes, b.face_sizes)
    assert "no room to move" in str(w[-1].message)
    # thinner columns there: the rings of the crossing joints move out (the
    # vertices differ), fewer pairs are left, and the warning says how many
    with pytest.warns(topomesh.GeometryWarning, match=r" 48 crossing triangle pairs \(160 before the rings of 24 vertices"):
        a = torus.wireframe_columns(0.05, 4)
    b = torus.wireframe_columns(0.05, 4, check_crossings=False)
    assert (len(a.self_intersections()), len(b.self_intersections())) == (48, 160)
    assert np.array_equal(a.face_indices, b.face_indices) and not np.array_equal(a.vertices, b.vertices)


def test_object_tools_counts():
    m = topomesh.dodecahedron()
    v, e, f, g = counts(m)
    s = m.subdivide_all_edges(2)
    assert counts(s) == (v + 2 * e, 3 * e, f, g)
    assert s.face_sizes.tolist() == [15] * f
    r = s.remove_valence2_vertices()
    assert counts(r) == counts(m)
    assert np.allclose(r.vertices, m.vertices)
    sp = topomesh.cube().subdivide_all_edges(1).split_valence2_vertices()
    assert counts(sp) == (8 + 24, 36, 6, 0)
    with pytest.raises(MeshError, match="n = 0"):
        m.subdivide_all_edges(0)


def test_cleanup_two_gons():
    c = topomesh.cube()
    m, _ = c.insert_edge(0, 0, 0, 1)  # a two-gon beside the first side
    assert 2 in m.face_sizes.tolist()
    r = m.cleanup_two_gons()
    assert counts(r) == counts(c)
    assert 2 not in r.face_sizes.tolist()


def test_planarize_residual_decreases():
    rng = np.random.default_rng(1)
    base = topomesh.cube().subdivide_all_edges(1)
    m = base.with_vertices(base.vertices + rng.normal(scale=0.05, size=base.vertices.shape))
    before = m.vertices.copy()
    r0 = m.planarity_residual()
    prev = r0
    cur = m
    for _ in range(4):
        cur, res = cur.planarize(iterations=3, tol=0.0)
        assert res < prev
        prev = res
    assert counts(cur) == counts(m)
    assert np.array_equal(m.vertices, before)
    _, res = m.planarize(iterations=500, tol=1e-8)
    assert res <= 1e-8 < r0
    with pytest.raises(MeshError, match="iterations"):
        m.planarize(iterations=-1)
    with pytest.raises(MeshError, match="tol"):
        m.planarize(tol=float("nan"))


def test_spherize():
    m = topomesh.cube().subdivide_all_edges(1).spherize(radius=2.0)
    c = m.vertices.mean(axis=0)
    assert np.allclose(np.linalg.norm(m.vertices - c, axis=1), 2.0)
    with pytest.raises(MeshError, match="radius"):
        topomesh.cube().spherize(radius=0.0)


def test_rind_by_scaling():
    m = topomesh.dodecahedron()
    r = m.rind_by_scaling(0.8)
    assert counts(r.mesh) == (40, 60, 24, 0)
    p = r.punch([0, 5])
    assert p.mesh.genus == 1 and p.mesh.n_components == 1
    check_watertight(p.mesh, 1)
    with pytest.raises(MeshError, match="scale"):
        m.rind_by_scaling(1.0)


def _face_at(m, p):
    c = m.face_centroids
    return int(np.argmin(np.linalg.norm(c - np.asarray(p), axis=1)))


def test_handle_pinch_keywords():
    m = topomesh.Mesh.from_polygons(*_grid_cube(3))
    top, bottom = _face_at(m, [0, 0, 1]), _face_at(m, [0, 0, -1])
    h0 = m.add_handle(top, bottom, segments=4, weights=(-1.0, -1.0))
    h1 = m.add_handle(top, bottom, segments=4, weights=(-1.0, -1.0), pinch=1.0, pinch_center=0.5, pinch_width=1.0, extra_twists=0)
    assert np.array_equal(h0.vertices, h1.vertices)
    h2 = m.add_handle(top, bottom, segments=4, weights=(-1.0, -1.0), pinch=0.5)
    assert counts(h2) == counts(h0) and h2.genus == 1
    nv = m.n_vertices
    mid0 = np.linalg.norm(h0.vertices[nv + 4 : nv + 8, :2], axis=1)
    mid2 = np.linalg.norm(h2.vertices[nv + 4 : nv + 8, :2], axis=1)
    assert np.allclose(mid2, 0.5 * mid0)
    h3 = m.add_handle(top, bottom, segments=8, weights=(-1.0, -1.0), extra_twists=1)
    assert h3.genus == 1
    for kw, val in [("pinch", 0.0), ("pinch_center", 1.0), ("pinch_width", 0.0), ("extra_twists", -1)]:
        with pytest.raises(MeshError, match=kw):
            m.add_handle(top, bottom, **{kw: val})


def test_multi_face_handle_cavity():
    # a 3x3-grid cube: three centre faces joined inside through a cavity hub
    g = topomesh.Mesh.from_polygons(*_grid_cube(3))
    sel = [_face_at(g, [0, 0, 1]), _face_at(g, [0, 0, -1]), _face_at(g, [1, 0, 0])]
    r = g.multi_face_handle(sel, scale=0.5, extrude=-0.5)
    assert r.genus == 2 and r.n_components == 1
    r.validate()
    check_watertight(r, 2)
    assert len(r.self_intersections()) == 0
    with pytest.raises(MeshError, match="at least 2"):
        g.multi_face_handle([sel[0]])
    with pytest.raises(MeshError, match="twice"):
        g.multi_face_handle([sel[0], sel[0]])
    with pytest.raises(MeshError, match="out of range"):
        g.multi_face_handle([0, 10**6])


def _grid_cube(n):
    pts, index, faces = [], {}, []

    def vid(p):
        if p not in index:
            index[p] = len(pts)
            pts.append([c * 2.0 / n - 1.0 for c in p])
        return index[p]

    for axis in range(3):
        for side in (0, n):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            for i in range(n):
                for j in range(n):
                    quad = []
                    for di, dj in [(0, 0), (1, 0), (1, 1), (0, 1)]:
                        p = [0, 0, 0]
                        p[axis], p[u], p[v] = side, i + di, j + dj
                        quad.append(vid(tuple(p)))
                    faces.append(quad[::-1] if side == 0 else quad)
    return np.array(pts), faces


def test_cuts():
    c = topomesh.cube()
    t = c.cut_vertices(list(range(8)), offset=0.25)
    assert counts(t) == (24, 36, 14, 0)
    check_watertight(t, 0)
    assert sorted(t.face_sizes.tolist()) == [3] * 8 + [8] * 6
    e = c.cut_edges(0, offset=0.25)
    assert counts(e) == (10, 15, 7, 0)
    f = c.cut_faces([0], offset=0.25)
    assert counts(f) == (8, 12, 6, 0)
    d = topomesh.dodecahedron().cut_vertices(range(20), offset=0.3)
    assert counts(d) == (60, 90, 32, 0)
    assert len(d.self_intersections()) == 0
    for call, arg in [(c.cut_vertices, 8), (c.cut_edges, 12), (c.cut_faces, 6)]:
        with pytest.raises(MeshError, match="out of range"):
            call(arg)
    with pytest.raises(MeshError, match="offset"):
        c.cut_vertices(0, offset=0.0)
    with pytest.raises(MeshError, match="twice"):
        c.cut_faces([1, 1])


@pytest.mark.parametrize("make", SHAPES)
def test_convex_hull_of_platonic_solids(make):
    m = make()
    h = topomesh.convex_hull(m)
    assert counts(h) == counts(m)
    assert sorted(h.face_sizes.tolist()) == sorted(m.face_sizes.tolist())
    check_watertight(h, 0)
    d = topomesh.dual_convex_hull(m.vertices)
    assert counts(d) == (m.n_faces, m.n_edges, m.n_vertices, 0)
    check_watertight(d, 0)


def test_convex_hull_points():
    rng = np.random.default_rng(3)
    pts = rng.normal(size=(500, 3))
    h = topomesh.convex_hull(pts)
    check_watertight(h, 0)
    ref = trimesh.convex.convex_hull(pts)
    assert h.n_vertices == len(ref.vertices)
    assert abs(h.to_trimesh().volume - ref.volume) < 1e-9 * ref.volume
    # grid points: six squares, interior and edge points dropped
    g, _ = _grid_cube(4)
    h = topomesh.convex_hull(np.vstack([g, [[0, 0, 0]]]))
    assert counts(h) == (8, 12, 6, 0)
    with pytest.raises(MeshError, match="one plane"):
        topomesh.convex_hull([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
    with pytest.raises(MeshError, match="at least 4"):
        topomesh.convex_hull([[0, 0, 0], [1, 0, 0], [0, 1, 0]])
    with pytest.raises(MeshError):
        topomesh.convex_hull([[0, 0, float("nan")]] * 5)


def test_open_meshes_refused_or_kept():
    pts = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    sq = topomesh.Mesh.from_polygons(pts, [[0, 1, 2, 3]])
    assert not sq.is_closed
    for call in (lambda m: m.wireframe(0.1), lambda m: m.cut_vertices(0)):
        with pytest.raises(MeshError, match="boundary"):
            call(sq)
    s = sq.subdivide_all_edges(1)
    assert (s.n_vertices, s.n_edges, s.n_boundary_loops) == (8, 8, 1)
    r = s.remove_valence2_vertices()
    assert r.n_boundary_loops == 1
    r.validate()
