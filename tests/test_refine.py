"""Honeycomb subdivision and vertex truncation: counts, histograms, genus,
positions against independent implementations of the papers' formulas,
planarity, and agreement with trimesh and manifold3d."""

from __future__ import annotations

from collections import Counter

import manifold3d as m3d
import numpy as np
import pytest
import trimesh

import topomesh
from tests.harness import PLATONIC, assert_agrees_with_peers


# --------------------------------------------------------------------- corpus


def prism(profile, height=0.6):
    """A prism over a counter-clockwise simple polygon (may be non-convex)."""
    p = np.asarray(profile, float)
    n = len(p)
    verts = np.vstack([np.c_[p, np.zeros(n)], np.c_[p, np.full(n, height)]])
    faces = [list(range(n))[::-1], list(range(n, 2 * n))]
    faces += [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    return topomesh.Mesh.from_polygons(verts, faces)


def star_prism():
    a = np.pi * np.arange(10) / 5
    r = np.where(np.arange(10) % 2 == 0, 1.0, 0.4)
    return prism(np.c_[r * np.cos(a), r * np.sin(a)], 0.5)


def l_prism():
    return prism([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], 0.7)


def loop_and_two_gon_cube():
    """A cube with a self-loop one-gon (InsertEdge on one corner twice) and a
    two-gon (an edge doubling a cube edge)."""
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 0)
    m, _ = m.insert_edge(3, 0, 3, 1)
    assert m.n_self_loops == 1
    assert m.face_size_histogram[1] == 1 and m.face_size_histogram[2] == 1
    return m


def handle_cube():
    """A cube whose faces 0 and 1 are merged by an edge (genus 1): the merged
    face runs along both sides of that edge and visits two vertices twice."""
    m, _ = topomesh.cube().insert_edge(0, 0, 1, 0)
    assert m.genus == 1 and m.face_size_histogram[10] == 1
    return m


CORPUS = {
    **PLATONIC,
    "torus": topomesh.torus,
    "genus3": lambda: topomesh.genus_surface(3),
    "loop_two_gon_cube": loop_and_two_gon_cube,
    "star_prism": star_prism,
    "handle_cube": handle_cube,
}
# inputs whose geometry is degenerate (zero-length loop) or self-intersecting
# (the handle edge runs through the cube): topology checks only
NO_PEERS = {"loop_two_gon_cube", "handle_cube"}


# --------------------------------------------------------------- peer checks



def size_hist(m: topomesh.Mesh) -> Counter:
    return Counter(m.face_size_histogram)


def max_planarity_deviation(m: topomesh.Mesh) -> float:
    """Largest distance of a face's corners from its least-squares plane,
    relative to the face's bounding-box diagonal."""
    v = m.vertices
    worst = 0.0
    start = 0
    idx = m.face_indices
    for s in m.face_sizes:
        p = v[idx[start : start + s]]
        start += s
        if s < 4:
            continue
        q = p - p.mean(axis=0)
        normal = np.linalg.svd(q)[2][-1]
        size = np.linalg.norm(p.max(axis=0) - p.min(axis=0))
        worst = max(worst, float(np.abs(q @ normal).max() / size))
    return worst


def face_rows(m: topomesh.Mesh) -> list[np.ndarray]:
    return np.split(m.face_indices, np.cumsum(m.face_sizes)[:-1])


# ------------------------------------------------------------------ honeycomb


@pytest.mark.parametrize("name", list(CORPUS))
def test_honeycomb_counts(name):
    m = CORPUS[name]()
    for _ in range(2):
        h = m.honeycomb()
        h.validate()
        V, E, F = m.n_vertices, m.n_edges, m.n_faces
        assert (h.n_vertices, h.n_edges, h.n_faces) == (2 * E, 3 * E, F + V)  # Remark 2
        assert h.genus == m.genus and h.n_components == m.n_components
        assert set(h.valence_histogram) == {3}
        want = size_hist(m)  # an n-gon stays an n-gon ...
        for k, c in m.valence_histogram.items():
            want[2 * k] += c  # ... a valence-k vertex becomes a 2k-gon
        assert size_hist(h) == want
        m = h


def test_honeycomb_of_platonic_solids():
    assert topomesh.dodecahedron().honeycomb().face_size_histogram == {5: 12, 6: 20}
    assert topomesh.icosahedron().honeycomb().face_size_histogram == {3: 20, 10: 12}
    assert topomesh.cube().honeycomb().face_size_histogram == {4: 6, 6: 8}
    assert topomesh.octahedron().honeycomb().face_size_histogram == {3: 8, 8: 6}
    assert topomesh.tetrahedron().honeycomb().face_size_histogram == {3: 4, 6: 4}
    # counts over iterations: F_n = F_{n-1} + V_{n-1}, E_n = 3 E_{n-1}, V_n = 2 E_{n-1}
    m = topomesh.dodecahedron()
    V, E, F = 20, 30, 12
    for n in range(1, 5):
        m = m.honeycomb()
        V, E, F = 2 * E, 3 * E, F + V
        assert (m.n_vertices, m.n_edges, m.n_faces) == (V, E, F)
    assert set(m.face_size_histogram) == {5, 6}
    assert m.face_size_histogram[5] == 12


@pytest.mark.parametrize("name", [n for n in CORPUS if n not in NO_PEERS])
def test_honeycomb_peers(name):
    h = CORPUS[name]().honeycomb(2)
    h.validate()
    assert_agrees_with_peers(h, planar=False)
    assert h.volume > 0


def honeycomb_reference(m: topomesh.Mesh, t: float, a: float | None) -> list[np.ndarray]:
    """Eq. (1)-(2) of the honeycomb paper summed directly (O(N^2) per face)."""
    v = m.vertices
    out = []
    for row in face_rows(m):
        N = len(row)
        p = (1 - t) * v[row] + t * v[np.roll(row, -1)]
        aa = 1.0 if N == 1 else (a if a is not None else min(1.0, 0.45 + 1.25 / N))
        W = np.empty((N, N))
        for n in range(N):
            for k in range(N):
                W[n, k] = aa if n == k else (3 + 2 * np.cos(2 * (n - k) * np.pi / N)) * (1 - aa) / (3 * N - 5)
        out.append(W @ p)
    return out


@pytest.mark.parametrize("t,a", [(0.5, None), (0.25, 0.6), (1.0, 0.0), (0.0, 1.0)])
@pytest.mark.parametrize("name", ["star_prism", "dodecahedron", "loop_two_gon_cube", "torus"])
def test_honeycomb_positions(name, t, a):
    m = CORPUS[name]()
    h = m.honeycomb(t=t, tension=a)
    # front face f of the result lists the new vertices of old face f's corners in order
    new_rows = face_rows(h)[: m.n_faces]
    for want, row in zip(honeycomb_reference(m, t, a), new_rows):
        np.testing.assert_allclose(h.vertices[row], want, rtol=0, atol=1e-12)


def test_honeycomb_weights_are_affine():
    # translating the input translates the output (weights sum to 1, every N)
    m = loop_and_two_gon_cube()
    shift = np.array([10.0, -3.0, 7.0])
    a = m.honeycomb(2).vertices
    b = m.with_vertices(m.vertices + shift).honeycomb(2).vertices
    np.testing.assert_allclose(b - shift, a, atol=1e-12)


def test_honeycomb_arguments():
    c = topomesh.cube()
    assert c.honeycomb(0) == c
    with pytest.raises(topomesh.MeshError, match="iterations"):
        c.honeycomb(-1)
    for bad in (-0.01, 1.01, float("nan")):
        with pytest.raises(topomesh.MeshError, match="t = "):
            c.honeycomb(t=bad)
        with pytest.raises(topomesh.MeshError, match="tension"):
            c.honeycomb(tension=bad)
    with pytest.raises(topomesh.MeshError, match="t = "):
        c.honeycomb(0, t=2.0)  # checked even for zero iterations


def test_progress_bar(capsys):
    m = topomesh.cube().honeycomb(3, progress=True)
    assert (m.n_vertices, m.n_edges, m.n_faces) == (216, 324, 110)
    err = capsys.readouterr().err
    assert "honeycomb" in err and "3/3" in err
    topomesh.cube().vertex_truncation(2, progress=True)
    assert "2/2" in capsys.readouterr().err


# ---------------------------------------------------------- vertex truncation

MODES = [dict(mode="chaikin"), dict(mode="polyhedral", ratio=0.1), dict(mode="polyhedral", ratio=0.5)]


@pytest.mark.parametrize("kw", MODES, ids=["chaikin", "poly0.1", "rectify"])
@pytest.mark.parametrize("name", list(CORPUS))
def test_truncation_counts(name, kw):
    m = CORPUS[name]()
    merged = kw.get("ratio") == 0.5
    for _ in range(2):
        t = m.vertex_truncation(**kw)
        t.validate()
        V, E, F = m.n_vertices, m.n_edges, m.n_faces
        if merged:
            assert (t.n_vertices, t.n_edges, t.n_faces) == (E, 2 * E, F + V)
            assert set(t.valence_histogram) == {4}
        else:
            assert (t.n_vertices, t.n_edges, t.n_faces) == (2 * E, 3 * E, F + V)
            assert set(t.valence_histogram) == {3}
        assert t.genus == m.genus and t.n_components == m.n_components
        want = Counter()
        for k, c in m.face_size_histogram.items():
            want[k if merged else 2 * k] += c  # n-gon -> 2n-gon (n-gon when merged)
        for k, c in m.valence_histogram.items():
            want[k] += c  # valence-m vertex -> m-gon
        assert size_hist(t) == want
        m = t


@pytest.mark.parametrize("kw", MODES, ids=["chaikin", "poly0.1", "rectify"])
@pytest.mark.parametrize("name", [n for n in CORPUS if n not in NO_PEERS])
def test_truncation_peers(name, kw):
    t = CORPUS[name]().vertex_truncation(2, **kw)
    t.validate()
    assert_agrees_with_peers(t, planar=False)
    assert t.volume > 0


def test_peers_on_loop_and_two_gon():
    # The input's self-loop has zero length and its one-gon and two-gon zero
    # area; their images keep coincident points (every cut of a zero-length
    # edge is its vertex). After three truncation steps the triangulation
    # stitches them (trimesh: watertight) and manifold3d merges the
    # coincident points. Honeycomb keeps the one-gon a one-gon (a point) for
    # ever; manifold3d still agrees on the genus and trimesh on the winding.
    m = loop_and_two_gon_cube()
    for kw in MODES:
        # coincident points of the zero-length loop: manifold3d merges them
        assert_agrees_with_peers(m.vertex_truncation(3, **kw), exact_vertices=False, planar=False)
    h = m.honeycomb(2)
    verts, tris, _ = h.triangulate()
    assert trimesh.Trimesh(verts, tris, process=False).is_winding_consistent
    man = m3d.Manifold(m3d.Mesh(vert_properties=verts.astype(np.float32), tri_verts=tris.astype(np.uint32)))
    assert man.status() == m3d.Error.NoError and man.genus() == h.genus == 0


@pytest.mark.parametrize("ratio", [0.1, 0.25, 0.4])
def test_truncation_positions(ratio):
    m = star_prism()
    t = m.vertex_truncation(mode="polyhedral", ratio=ratio)
    v = m.vertices
    for row, new in zip(face_rows(m), face_rows(t)[: m.n_faces]):
        a, b = v[row], v[np.roll(row, -1)]
        want = np.empty((2 * len(row), 3))
        want[0::2] = (1 - ratio) * a + ratio * b
        want[1::2] = ratio * a + (1 - ratio) * b
        np.testing.assert_allclose(t.vertices[new], want, atol=1e-15)
    # chaikin is the polyhedral cut at 1/4
    assert m.vertex_truncation() == m.vertex_truncation(mode="polyhedral", ratio=0.25)


@pytest.mark.parametrize("name", list(PLATONIC))
def test_truncation_planar_platonic(name):
    m = CORPUS[name]()
    assert max_planarity_deviation(m) < 1e-12
    for i in range(5):
        m = m.vertex_truncation()
        assert max_planarity_deviation(m) < 1e-12, (name, i)


@pytest.mark.parametrize("make", [star_prism, l_prism], ids=["star", "L"])
def test_truncation_planar_nonconvex(make):
    m = make()
    assert set(m.valence_histogram) == {3}
    for _ in range(4):
        m = m.vertex_truncation()
        assert max_planarity_deviation(m) < 1e-12
    assert m.volume > 0


def test_truncation_nonplanar_input_gives_nonplanar_faces():
    # torus vertices are 4-valent and not symmetric: their cut points are not coplanar
    assert max_planarity_deviation(topomesh.torus().vertex_truncation()) > 1e-3


def test_archimedean_truncations():
    def edge_lengths(m):
        e = m.edges
        return np.linalg.norm(m.vertices[e[:, 0]] - m.vertices[e[:, 1]], axis=1)

    for make, n, hist in [
        (topomesh.tetrahedron, 3, {3: 4, 6: 4}),
        (topomesh.cube, 4, {3: 8, 8: 6}),
        (topomesh.dodecahedron, 5, {3: 20, 10: 12}),
        (topomesh.icosahedron, 3, {5: 12, 6: 20}),
    ]:
        t = make().vertex_truncation(mode="polyhedral", ratio=1 / (2 + 2 * np.cos(np.pi / n)))
        assert t.face_size_histogram == hist
        L = edge_lengths(t)
        assert L.max() - L.min() < 1e-12 * L.max()
    co = topomesh.cube().vertex_truncation(mode="polyhedral", ratio=0.5)
    assert co.face_size_histogram == {3: 8, 4: 6}  # cuboctahedron
    L = edge_lengths(co)
    assert L.max() - L.min() < 1e-12
    ico = topomesh.dodecahedron().vertex_truncation(mode="polyhedral", ratio=0.5)
    assert ico.face_size_histogram == {3: 20, 5: 12}  # icosidodecahedron


def test_truncation_arguments():
    c = topomesh.cube()
    assert c.vertex_truncation(0) == c
    with pytest.raises(topomesh.MeshError, match="iterations"):
        c.vertex_truncation(-2)
    with pytest.raises(topomesh.MeshError, match="mode"):
        c.vertex_truncation(mode="catmull")
    with pytest.raises(topomesh.MeshError, match="ratio"):
        c.vertex_truncation(ratio=0.3)  # chaikin cuts at 1/4 only
    for bad in (0.0, -0.1, 0.51, float("nan")):
        with pytest.raises(topomesh.MeshError, match="ratio"):
            c.vertex_truncation(mode="polyhedral", ratio=bad)


@pytest.mark.parametrize("scheme", ["catmull_clark", "loop", "doo_sabin", "midpoint", "dual"])
def test_schemes_with_boundary_rules_keep_holes(scheme):
    box = topomesh.Mesh.from_polygons(topomesh.cube().vertices, face_rows(topomesh.cube())[1:])
    out = getattr(box, scheme)(2)
    out.validate()
    assert out.n_boundary_loops == 1 and not out.is_closed
    assert out.euler_characteristic == box.euler_characteristic == 1


def test_point_spheres_and_holes_pass_through():
    m, _, _ = topomesh.cube().create_vertex([5.0, 0.0, 0.0])
    for out in (m.honeycomb(2), m.vertex_truncation(2), m.vertex_truncation(mode="polyhedral", ratio=0.5)):
        out.validate()
        assert out.n_components == 2 and out.component_genera == [0, 0]
        assert [5.0, 0.0, 0.0] in out.vertices.tolist()
    box = topomesh.Mesh.from_polygons(topomesh.cube().vertices, face_rows(topomesh.cube())[1:], close_boundaries=True)
    for out in (box.honeycomb(), box.vertex_truncation(2)):
        out.validate()
        assert out.n_holes == 1
        assert len(out.face_sizes) == out.n_faces - 1  # the hole is not exported


@pytest.mark.parametrize("scheme", ["sierpinski", "menger"])
def test_schemes_without_boundary_rules_refuse_holes(scheme):
    # a capped hole must not become a real face: these schemes have no boundary rule
    box = topomesh.Mesh.from_polygons(topomesh.cube().vertices, face_rows(topomesh.cube())[1:], close_boundaries=True)
    with pytest.raises(topomesh.MeshError, match=rf"^{scheme}: the mesh has 1 boundary loop"):
        getattr(box, scheme)()
