"""High-level operators (ch. III), curved handles (ch. IV) and rinds (ch. V.3)
of the high-genus dissertation: contracts on V, E, F, genus; peers
(trimesh, manifold3d) on the geometric examples; no self-intersecting triangles."""

from __future__ import annotations

import numpy as np
import pytest

import topomesh
from topomesh import Mesh, MeshError
from tests.harness import assert_agrees_with_peers


# ------------------------------------------------------------------ shapes

from topomesh.modeling import (  # noqa: E402
    arch_cube,
    cube_sphere,
    cup,
    edge_between as edge_index,
    face_at,
    grid_cube,
    peeled_rind_sphere,
    triangle_hexagon_handle,
)


def face_rows(m: Mesh) -> list[list[int]]:
    sizes, idx = m.face_sizes, m.face_indices
    off = np.concatenate([[0], np.cumsum(sizes)])
    return [list(idx[off[i]:off[i + 1]]) for i in range(len(sizes))]


def counts(m: Mesh):
    m.validate()
    return (m.n_vertices, m.n_edges, m.n_faces, m.n_components, m.genus)


# --------------------------------------------------- self-intersection check


def _cross(a, b):
    return np.cross(a, b)


def _dot(a, b):
    return np.einsum("ij,ij->i", a, b)


def _segments_hit_triangles(p0, p1, a, b, c, eps=1e-9):
    """Möller–Trumbore for K segments p0→p1 against K triangles abc; coplanar
    pairs (det ≈ 0) report False here and are handled separately."""
    d = p1 - p0
    e1, e2 = b - a, c - a
    h = _cross(d, e2)
    det = _dot(e1, h)
    scale = np.linalg.norm(d, axis=1) * np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1) + 1e-300
    ok = np.abs(det) > 1e-12 * scale
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = p0 - a
    u = inv * _dot(s, h)
    q = _cross(s, e1)
    v = inv * _dot(d, q)
    t = inv * _dot(e2, q)
    return ok & (u >= -eps) & (v >= -eps) & (u + v <= 1 + eps) & (t >= -eps) & (t <= 1 + eps)


def _coplanar_overlap(t1, t2, eps=1e-9) -> bool:
    """Two coplanar triangles (3, 3) overlap (edges cross or one holds a
    vertex of the other), in the plane of t1."""
    n = np.cross(t1[1] - t1[0], t1[2] - t1[0])
    drop = int(np.argmax(np.abs(n)))
    keep = [i for i in range(3) if i != drop]
    p, q = t1[:, keep], t2[:, keep]

    def orient(a, b, c):
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])

    for i in range(3):
        for j in range(3):
            a, b, c, d = p[i], p[(i + 1) % 3], q[j], q[(j + 1) % 3]
            o1, o2, o3, o4 = orient(a, b, c), orient(a, b, d), orient(c, d, a), orient(c, d, b)
            if o1 * o2 < -eps and o3 * o4 < -eps:
                return True

    def inside(x, tri):
        s = [orient(tri[k], tri[(k + 1) % 3], x) for k in range(3)]
        return all(v > eps for v in s) or all(v < -eps for v in s)

    return any(inside(x, p) for x in q) or any(inside(x, q) for x in p)


def self_intersections(m: Mesh) -> list[tuple[int, int]]:
    """Pairs of triangles of ``m.triangulate()`` that intersect improperly."""
    verts, tris, _ = m.triangulate()
    return triangle_intersections(verts, tris)


def triangle_intersections(v: np.ndarray, t: np.ndarray, chunk: int = 256) -> list[tuple[int, int]]:
    """Pairs of triangles ``t`` (T, 3) over vertices ``v`` that intersect improperly: a
    bounding-box prefilter (numpy, chunked), then segment–triangle tests
    (Möller–Trumbore) both ways. Pairs sharing no vertex: every side of each
    against the other, plus a planar test for coplanar pairs. Pairs sharing
    exactly one vertex: the side opposite the shared vertex of each against
    the other (the other sides meet the other triangle's plane only at the
    shared vertex, unless coplanar). Pairs sharing a side are neighbours."""
    tri = v[t]  # (T, 3, 3)
    lo, hi = tri.min(axis=1), tri.max(axis=1)
    tol = 1e-9 * max(1.0, float(np.abs(v).max()))
    pairs = []
    for s in range(0, len(t), chunk):
        blo, bhi = lo[s:s + chunk, None, :], hi[s:s + chunk, None, :]
        over = np.all((blo <= hi[None, :, :] + tol) & (lo[None, :, :] <= bhi + tol), axis=2)
        i, j = np.nonzero(over)
        i = i + s
        keep = j > i
        pairs.append(np.stack([i[keep], j[keep]], axis=1))
    cand = np.concatenate(pairs) if pairs else np.zeros((0, 2), int)
    same = np.zeros((len(cand), 3, 3), bool)  # same[k, a, b]: corner a of the first is corner b of the second
    for a in range(3):
        for b in range(3):
            same[:, a, b] = t[cand[:, 0], a] == t[cand[:, 1], b]
    shared = same.any(axis=2).sum(axis=1)
    found = []
    # no shared vertex
    c0 = cand[shared == 0]
    if len(c0):
        A, B = tri[c0[:, 0]], tri[c0[:, 1]]
        hit = np.zeros(len(c0), bool)
        for k in range(3):
            hit |= _segments_hit_triangles(A[:, k], A[:, (k + 1) % 3], B[:, 0], B[:, 1], B[:, 2])
            hit |= _segments_hit_triangles(B[:, k], B[:, (k + 1) % 3], A[:, 0], A[:, 1], A[:, 2])
        n1 = np.cross(A[:, 1] - A[:, 0], A[:, 2] - A[:, 0])
        n1 /= np.linalg.norm(n1, axis=1, keepdims=True) + 1e-300
        dist = np.abs(np.einsum("ikj,ij->ik", B - A[:, :1], n1))
        cop = np.all(dist < tol * 10, axis=1) & ~hit
        for k in np.nonzero(cop)[0]:
            hit[k] = _coplanar_overlap(A[k], B[k])
        found += [tuple(p) for p in c0[hit]]
    # one shared vertex: the opposite sides
    sel = shared == 1
    c1 = cand[sel]
    if len(c1):
        ia = np.argmax(same[sel].any(axis=2), axis=1)  # shared corner in the first
        ib = np.argmax(same[sel].any(axis=1), axis=1)  # and in the second
        r = np.arange(len(c1))
        A, B = tri[c1[:, 0]], tri[c1[:, 1]]
        hit = _segments_hit_triangles(A[r, (ia + 1) % 3], A[r, (ia + 2) % 3], B[:, 0], B[:, 1], B[:, 2])
        hit |= _segments_hit_triangles(B[r, (ib + 1) % 3], B[r, (ib + 2) % 3], A[:, 0], A[:, 1], A[:, 2])
        found += [tuple(p) for p in c1[hit]]
    return sorted(found)


def assert_clean(m: Mesh, genus: int | None = None) -> None:
    """Peers agree on topology, and no two triangles cross."""
    assert_agrees_with_peers(m, expect_genus=genus)
    bad = self_intersections(m)
    assert not bad, f"{len(bad)} intersecting triangle pairs, e.g. {bad[:3]}"


def test_intersection_check_finds_crossings():
    # two disjoint-vertex triangles crossing each other, and two that do not
    v = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0.5, 0.5, -1], [0.5, 0.5, 1], [1.5, 1.5, 0.0],
                  [5, 5, 5], [6, 5, 5], [5, 6, 5]], float)
    m = Mesh.from_polygons(v, [[0, 1, 2], [3, 4, 5], [6, 7, 8]], close_boundaries=True)
    assert self_intersections(m) == [(0, 1)]
    # coplanar overlap
    v = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0.5, 0.2, 0], [3, 0.2, 0], [0.5, 3, 0]], float)
    m = Mesh.from_polygons(v, [[0, 1, 2], [3, 4, 5]], close_boundaries=True)
    assert self_intersections(m) == [(0, 1)]
    # sharing one vertex, the second folded through the first
    v = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [1, 1, -1], [0.2, 0.2, 1]], float)
    t = np.array([[0, 1, 2], [0, 3, 4]])
    assert triangle_intersections(v, t) == [(0, 1)]
    v[4] = [-2, 1, 1]  # now they only meet at vertex 0
    assert triangle_intersections(v, t) == []
    # sharing a side: neighbours, never reported
    assert triangle_intersections(v, np.array([[0, 1, 2], [0, 2, 3]])) == []
    assert self_intersections(grid_cube(3)) == []


# ------------------------------------------------------ operator contracts


def test_delete_edge_with_cleanup():
    m = topomesh.cube()
    assert counts(m.delete_edge_with_cleanup(0)) == (8, 11, 5, 1, 0)
    # a dangling edge to a point-sphere: the vertex goes with it
    m2, v, f = m.create_vertex([0, 0, 0])
    m3, e = m2.insert_edge(0, 0, f, 0)
    assert counts(m3) == (9, 13, 6, 1, 0)
    assert counts(m3.delete_edge_with_cleanup(e)) == (8, 12, 6, 1, 0)
    assert counts(m3.delete_edge(e)) == (9, 12, 7, 2, 0)
    with pytest.raises(MeshError, match="edge 99 out of range"):
        m.delete_edge_with_cleanup(99)


def test_subdivide_edge_contract_and_degenerate():
    m = topomesh.cube()
    a, b = m.edges[3]
    s, v = m.subdivide_edge(3, t=0.25)
    assert counts(s) == (9, 13, 6, 1, 0)
    assert np.allclose(s.vertices[v], 0.75 * m.vertices[a] + 0.25 * m.vertices[b])
    assert s.face_size_histogram == {4: 4, 5: 2}
    # self-loop: a one-gon becomes a two-gon; two-gon becomes a triangle
    m, _, _ = topomesh.cube().create_face_manifold([[0, 0, 5], [1, 0, 5]])  # a two-gon sphere
    assert m.face_size_histogram == {2: 2, 4: 6}
    s, _ = m.subdivide_edge(m.n_edges - 1)  # an edge of the two-gon sphere
    assert counts(s) == (11, 15, 8, 2, 0) and s.face_size_histogram == {3: 2, 4: 6}
    m, f = topomesh.cube().insert_edge(0, 0, 0, 0)  # a self-loop in face 0
    assert m.n_self_loops == 1
    s, _ = m.subdivide_edge(m.n_edges - 1)
    assert counts(s) == (9, 14, 7, 1, 0) and s.n_self_loops == 0
    with pytest.raises(MeshError, match="not in"):
        topomesh.cube().subdivide_edge(0, t=2.0)


def test_create_pipe_contracts():
    m = topomesh.cube()
    # a pipe between opposite faces of the bare cube: its walls lie on the
    # side faces (coplanar overlap), which the crossing check reports
    with pytest.warns(topomesh.GeometryWarning, match="create_pipe: the new faces pass through the surface"):
        p = m.create_pipe(0, 0, 1, 0)
    assert counts(p) == (8, 16, 8, 1, 1)
    # triangle to hexagon across two components: three splits first
    # (the pyramid is given inside out, which the constructor reports)
    with pytest.warns(topomesh.GeometryWarning, match="inside out"):
        pyramid = Mesh.from_polygons(
            [[np.cos(a), np.sin(a), 0] for a in np.arange(6) * np.pi / 3] + [[0, 0, 1]],
            [[0, 1, 2, 3, 4, 5], [0, 6, 1], [1, 6, 2], [2, 6, 3], [3, 6, 4], [4, 6, 5], [5, 6, 0]],
        )
    m, front, back = pyramid.create_face_manifold([[0, 0, -3], [1, 0, -3], [0, 1, -3]])
    v, e, f, c, g = counts(m)
    assert m.face_sizes[0] == 6
    # the flat two-face sphere's back face lies in the pipe's end: the pipe's
    # quads cross it (the independent numpy check finds crossings too)
    with pytest.warns(topomesh.GeometryWarning, match=r"create_pipe: .* (\d+) crossing triangle pairs") as w:
        p = m.create_pipe(0, 0, front, 0)
    assert str(len(p.self_intersections())) in str(w[0].message)
    assert len(self_intersections(p)) > 0
    assert counts(p) == (v + 3, e + 3 + 6, f + 4, c - 1, g)
    # degenerate: two-gons of a two-gon sphere; one-gons of a self-loop sphere
    m, a, b = topomesh.cube().create_face_manifold([[0, 0, 5], [1, 0, 5]])
    assert counts(m.create_pipe(a, 0, b, 0)) == (10, 16, 8, 2, 1)
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 0)
    loop_face = m.n_faces - 1
    assert m.face_sizes[loop_face] == 1
    # the pipe from a point (the loop's vertex, a corner of face 1) lies flat
    # in face 1's plane: a degenerate, self-overlapping shape, reported
    with pytest.warns(topomesh.GeometryWarning, match="create_pipe: the new faces pass through the surface"):
        p = m.create_pipe(loop_face, 0, 1, 0)
    assert counts(p) == (11, 13 + 3 + 4, 7 + 2, 1, 1)
    assert len(self_intersections(p)) > 0
    with pytest.raises(MeshError, match="both corners are in face 2"):
        topomesh.cube().create_pipe(2, 0, 2, 1)
    with pytest.raises(MeshError, match="face 2 has 4 corners; position 9"):
        topomesh.cube().create_pipe(2, 9, 3, 0)


def test_create_face_manifold_and_connect_edges():
    m, front, back = topomesh.cube().create_face_manifold([[0, 0, 3], [1, 0, 3], [1, 1, 3], [0, 1, 3]])
    assert counts(m) == (12, 16, 8, 2, 0)
    assert m.face_normals[front][2] > 0.99 and m.face_normals[back][2] < -0.99
    # connect two sides of one face: it splits in three
    s, f = topomesh.cube().connect_edges(0, 0, 0, 2)
    assert counts(s) == (8, 14, 8, 1, 0) and s.face_sizes[f] == 4
    # two faces: a handle, F unchanged
    s, f = topomesh.cube().connect_edges(0, 0, 1, 0)
    assert counts(s) == (8, 14, 6, 1, 1)
    # two-gon sides and one-gons
    m, a, b = Mesh.from_polygons([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 1]]).create_face_manifold([[0, 0, 5], [1, 0, 5]])
    assert counts(m.connect_edges(a, 0, b, 0)[0]) == (5, 7, 4, 2, 1)
    with pytest.raises(MeshError, match="both half-edges"):
        topomesh.cube().connect_edges(0, 1, 0, 1)


def test_collapse_edge():
    ico = topomesh.icosahedron()
    a, b = ico.edges[0]
    m, v = ico.collapse_edge(0)
    assert counts(m) == (11, 29, 20, 1, 0)
    assert m.face_size_histogram == {2: 2, 3: 18}
    assert np.allclose(m.vertices[v], (ico.vertices[a] + ico.vertices[b]) / 2)
    t = topomesh.torus(6, 4)
    assert counts(t.collapse_edge(5)[0]) == (23, 47, 24, 1, 1)
    # an edge with a two-gon beside it: s = 2
    c, e = topomesh.cube().insert_edge(0, 0, 0, 1)
    assert c.face_size_histogram[2] == 1
    assert counts(c.collapse_edge(e)[0]) == (7, 11, 6, 1, 0)
    c, e = topomesh.cube().insert_edge(0, 0, 0, 0)
    with pytest.raises(MeshError, match="self-loop"):
        c.collapse_edge(e)


# ------------------------------------------------------------------ handles


def test_torus_from_one_handle_on_a_cube():
    m = grid_cube(3)
    a, b = face_at(m, [-2 / 3, 0, 1]), face_at(m, [2 / 3, 0, 1])
    v, e, f, c, g = counts(m)
    h = m.add_handle(a, b, segments=6, weights=(2.5, 2.5))
    n, k = 4, 6
    assert counts(h) == (v + n * (k - 1), e + n * (2 * k - 1), f + n * k - 2, 1, 1)
    assert_clean(h, genus=1)
    # a tunnel through the cube: negative weights
    t = m.add_handle(face_at(m, [0, 0, 1]), face_at(m, [0, 0, -1]), segments=3, weights=(-1.0, -1.0))
    assert t.volume < m.volume
    assert_clean(t, genus=1)


def test_handle_through_the_body_warns_with_the_crossing_count():
    # small positive weights: the handle's first segment folds through itself
    # and the body (the independent numpy check finds the same defect)
    m = grid_cube(3)
    top, bottom = face_at(m, [0, 0, 1]), face_at(m, [0, 0, -1])
    for w in [(0.5, 0.5), (2.5, 2.5)]:
        with pytest.warns(topomesh.GeometryWarning, match=r"add_handle: the new faces pass through the surface: \d+ crossing"):
            h = m.add_handle(top, bottom, segments=6, weights=w)
        ours = h.self_intersections()
        assert len(ours) > 0 and len(self_intersections(h)) > 0
        # every pair the shared check reports is a real contact of two triangles
        tris = h.triangles()
        assert np.all(ours[:, 0] < ours[:, 1]) and ours.max() < len(tris)
    # a clean tunnel: no warning (pytest turns one into an error), no pair
    t = m.add_handle(top, bottom, segments=3, weights=(-1.0, -1.0))
    assert len(t.self_intersections()) == 0 and self_intersections(t) == []


def test_self_intersections_agrees_with_the_numpy_check():
    v = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0.5, 0.5, -1], [0.5, 0.5, 1], [1.5, 1.5, 0.0],
                  [5, 5, 5], [6, 5, 5], [5, 6, 5]], float)
    m = Mesh.from_polygons(v, [[0, 1, 2], [3, 4, 5], [6, 7, 8]], close_boundaries=True)
    assert m.self_intersections().tolist() == [[0, 1]] == [list(p) for p in self_intersections(m)]
    # coplanar overlap counts too
    v = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0.5, 0.2, 0], [3, 0.2, 0], [0.5, 3, 0]], float)
    m = Mesh.from_polygons(v, [[0, 1, 2], [3, 4, 5]], close_boundaries=True)
    assert m.self_intersections().tolist() == [[0, 1]]
    for clean in (grid_cube(3), topomesh.torus(), topomesh.genus_surface(2)):
        assert len(clean.self_intersections()) == 0


def test_genus_three_cube_with_three_handles():
    m = arch_cube(3)
    assert (m.genus, m.n_components) == (3, 1)
    assert_clean(m, genus=3)


def test_twisted_handle():
    m = grid_cube(5)
    a, b = face_at(m, [-0.8, 0, 1]), face_at(m, [0.8, 0, 1])
    straight = m.add_handle(a, b, segments=8, weights=(3.0, 3.0))  # corners=(0, None): least twist
    others = [m.add_handle(a, b, segments=8, weights=(3.0, 3.0), corners=(0, j)) for j in range(4)]
    # one choice of corner is the untwisted one; the others twist by quarter turns
    assert sum(np.allclose(o.vertices, straight.vertices) for o in others) == 1
    assert any(not np.allclose(o.vertices, straight.vertices) for o in others)
    assert_clean(straight, genus=1)
    for o in others:
        if not np.allclose(o.vertices, straight.vertices):
            assert_clean(o, genus=1)
    assert np.allclose(arch_cube(1).vertices, straight.vertices)
    assert any(np.allclose(arch_cube(1, twist=1).vertices, o.vertices) for o in others)


def triangle_and_hexagon(m: Mesh) -> tuple[Mesh, int, int]:
    """A grid cube with a triangle at (−0.8, 0, 1) and a hexagon at (0.8, 0, 1)."""
    fa = face_at(m, [-0.8, 0, 1])
    m, _ = m.insert_edge(fa, 0, fa, 2)  # split the quad into two triangles
    fb = face_at(m, [0.8, 0, 1])
    rows = face_rows(m)
    q = rows[fb]
    for a, b in ((q[0], q[1]), (q[2], q[3])):
        m, _ = m.subdivide_edge(edge_index(m, a, b))
    hexa = int(np.nonzero(m.face_sizes == 6)[0][0])
    tri = [f for f in range(m.n_faces) if m.face_sizes[f] == 3]
    assert len(tri) == 2
    return m, tri[0], hexa


def test_triangle_to_hexagon_handle():
    m, tri, hexa = triangle_and_hexagon(grid_cube(5))
    v, e, f, c, g = counts(m)
    h = m.add_handle(tri, hexa, segments=8, weights=(3.0, 3.0))
    n, k, d = 6, 8, 3
    assert counts(h) == (v + d + n * (k - 1), e + d + n * (2 * k - 1), f + n * k - 2, 1, 1)
    assert_clean(h, genus=1)
    assert h == triangle_hexagon_handle()


def test_handle_between_two_components():
    m = grid_cube(3)
    two = Mesh.from_flat(
        np.concatenate([m.vertices, m.vertices + [0, 0, 4]]),
        np.concatenate([m.face_sizes, m.face_sizes]),
        np.concatenate([m.face_indices, m.face_indices + m.n_vertices]),
    )
    top, bottom = face_at(two, [0, 0, 1]), face_at(two, [0, 0, 3])
    h = two.add_handle(top, bottom, segments=3, weights=(1.0, 1.0))
    assert (h.n_components, h.genus) == (1, 0)
    assert_clean(h, genus=0)


def test_handle_errors():
    m = grid_cube(3)
    a = face_at(m, [0, 0, 1])
    with pytest.raises(MeshError, match="share an edge"):
        m.add_handle(a, face_at(m, [2 / 3, 0, 1]))
    with pytest.raises(MeshError, match="both corners are in face"):
        m.add_handle(a, a)
    with pytest.raises(MeshError, match="one sign"):
        m.add_handle(a, face_at(m, [0, 0, -1]), weights=(1.0, -1.0))
    with pytest.raises(MeshError, match="position 7 is out of range"):
        m.add_handle(a, face_at(m, [0, 0, -1]), corners=(7, 0))
    with pytest.raises(MeshError, match="segments"):
        m.add_handle(a, face_at(m, [0, 0, -1]), segments=0)


# -------------------------------------------------------------------- rinds


def centre_faces(m: Mesh) -> list[int]:
    c = m.face_centroids
    return [f for f in range(m.n_faces) if abs(np.linalg.norm(c[f]) - 1) < 1e-9]


@pytest.mark.parametrize("holes, genus", [(1, 0), (2, 1), (6, 5)])
def test_rind_cube_with_holes(holes, genus):
    m = grid_cube(3)
    r = m.rind(0.2)
    assert (r.mesh.n_components, r.mesh.genus) == (2, 0)
    faces = centre_faces(m)[:holes]
    p = r.punch(faces)
    assert p.punched == sorted(faces)
    assert counts(p.mesh)[3:] == (1, genus)
    assert_clean(p.mesh, genus=genus)


def test_peeled_rind_strip():
    m = grid_cube(3)
    c = m.face_centroids
    strip = sorted((f for f in range(m.n_faces) if abs(c[f][2] - 1) < 1e-9 and abs(c[f][1]) < 1e-9), key=lambda f: c[f][0])
    assert len(strip) == 3
    r = m.rind(0.2)
    punched = r.punch(strip)
    assert punched.mesh.genus == 2  # two thin walls, each a handle
    peeled = r.peel(strip)
    assert counts(peeled.mesh)[3:] == (1, 0)
    assert punched.mesh.n_edges - peeled.mesh.n_edges == 2 * 4
    assert_clean(peeled.mesh, genus=0)
    # a 2 × 2 block around a vertex: one hole, its centre vertex pair gone
    m = grid_cube(4)
    c = m.face_centroids
    block = [f for f in range(m.n_faces) if abs(c[f][2] - 1) < 1e-9 and abs(c[f][0]) < 0.5 and abs(c[f][1]) < 0.5]
    r = m.rind(0.1)
    peeled = r.peel(block)
    assert peeled.mesh.n_vertices == r.mesh.n_vertices - 2
    assert_clean(peeled.mesh, genus=0)
    # peeling a second strip elsewhere: two holes, genus 1
    both = peeled.peel([face_at(m, [0.75, 0.25, -1]), face_at(m, [0.25, 0.25, -1])])
    assert_clean(both.mesh, genus=1)


def test_rind_errors():
    m = topomesh.cube()
    with pytest.raises(MeshError, match="thickness"):
        m.rind(-0.1)
    with pytest.raises(MeshError, match="flips the inner twin of face"):
        m.rind(2.0)
    r = m.rind(0.3)
    with pytest.raises(MeshError, match="face 8 is on the inner shell"):
        r.punch(8)
    with pytest.raises(MeshError, match="out of range"):
        r.punch([12])
    r2 = r.punch(3)
    with pytest.raises(MeshError, match="face 3 is already punched"):
        r2.peel([3])
    with pytest.raises(MeshError, match="twice"):
        r.punch([1, 1])
    assert r.face_pair(3) == (3, 9) and r2.face_pair(3) is None


def test_cup():
    m = cup()
    assert (m.n_components, m.genus) == (1, 1)
    assert_clean(m, genus=1)


def test_peeled_rind_sphere():
    g = grid_cube(6)
    sphere = cube_sphere(6)
    c = g.face_centroids
    window = [f for f in range(g.n_faces) if np.sort(np.abs(c[f]))[1] < 0.34]  # 2 × 2 per side
    assert len(window) == 24
    r = sphere.rind(0.12)
    assert r.punch(window).mesh.genus == 23
    peeled = r.peel(window)
    assert peeled.mesh.n_vertices == r.mesh.n_vertices - 2 * 6  # each window's centre vertex pair
    assert_clean(peeled.mesh, genus=5)
    assert peeled.mesh == peeled_rind_sphere()
