"""Smoothing and refinement schemes: counts, validity, peers, positions.

Peers and what they are compared on (positions up to vertex order):

* Loop — ``trimesh.remesh.subdivide_loop`` (Loop's original beta, float64):
  1e-9 relative on triangle meshes; on polygon meshes against trimesh run on
  the same centroid fan (topomesh's "extended Loop"). pymeshlab (float32
  inside): 1e-6.
* midpoint — ``trimesh.remesh.subdivide`` (float64), 1e-9, triangles.
* Catmull-Clark — pyOpenSubdiv (OpenSubdiv, float32 inside): 1e-6 relative;
  an independent float64 implementation of the 1978 masks below: 1e-9.
  pymeshlab's Catmull-Clark differs by design (its cube corner goes to
  11/18, the 1978 rule and OpenSubdiv give 5/9), so it is not a reference.
* Doo-Sabin — pymeshlab (float32): 1e-6 on the Platonic solids, whose faces
  are regular; on other faces pymeshlab's points differ (up to 2e-2 on the
  torus), so the reference there is the independent float64 implementation
  of Doo & Sabin's weights below (1e-9).
* sqrt3, simplest, dual — no library implements them: independent
  implementations below (1e-9), sqrt3 with its triangles too.

Peer validation (trimesh watertight + winding, manifold3d status + genus)
runs on the triangulated outputs. It cannot judge outputs with multi-edges or
zero-area flaps (peers index edges by vertex pair), which Loop makes of a
two-gon and the primal schemes make of a one-gon; those cases are checked with
``validate()`` and the count formulas only.
"""

from __future__ import annotations

import importlib.util
from collections import Counter

import numpy as np
import pytest
import trimesh
import manifold3d
from scipy.spatial import cKDTree

import topomesh
from topomesh import Mesh, MeshError
from tests.harness import PLATONIC

SCHEMES = ["catmull_clark", "doo_sabin", "loop", "sqrt3", "simplest", "midpoint", "dual"]


# ----------------------------------------------------------------- corpus


def faces_of(m: Mesh) -> list[list[int]]:
    return [list(map(int, f)) for f in np.split(m.face_indices, np.cumsum(m.face_sizes)[:-1])]


def self_loop_cube() -> Mesh:
    """A zero-length self-loop cutting a one-gon off a cube face."""
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 0)
    return m


def two_gon_cube() -> Mesh:
    """A second edge along a cube edge: a two-gon and a multi-edge."""
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 1)
    return m


def handle_loop_cube() -> Mesh:
    """A zero-length self-loop joining two faces at one vertex, as in
    Sierpinski output: the faces merge, genus 1."""
    c = topomesh.cube()
    fs = faces_of(c)
    v = fs[0][0]
    f2 = next(i for i, f in enumerate(fs) if i > 0 and v in f)
    m, _ = c.insert_edge(0, 0, f2, fs[f2].index(v))
    return m


def sierpinski_tetrahedron() -> Mesh:
    """Level 1 of the Sierpinski paper's scheme on the tetrahedron, built
    directly: four corner tetrahedra whose back faces are hexagons
    ``[x, x, y, y, z, z]`` with a zero-length self-loop at each midpoint; each
    loop joins the back faces of two corner pyramids. Genus 3."""
    t = topomesh.tetrahedron()
    T = t.vertices
    V = list(T)
    mid: dict[tuple[int, int], int] = {}

    def m(a: int, b: int) -> int:
        k = (min(a, b), max(a, b))
        if k not in mid:
            mid[k] = len(V)
            V.append((T[a] + T[b]) / 2)
        return mid[k]

    F = []
    for a, b, c in faces_of(t):
        F += [[a, m(a, b), m(c, a)], [b, m(b, c), m(a, b)], [c, m(c, a), m(b, c)]]
    for a in range(4):
        x, y, z = [m(a, o) for o in range(4) if o != a]
        if np.dot(np.cross(V[y] - V[x], V[z] - V[x]), V[x] - T[a]) < 0:
            y, z = z, y
        F.append([x, x, y, y, z, z])
    return Mesh.from_polygons(np.array(V), F)


def dihedron(n: int) -> Mesh:
    """Two n-gons glued along their whole boundary: every vertex has valence 2."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    V = np.column_stack([np.cos(t), np.sin(t), 0.1 * np.sin(3 * t)])
    # the second face starts at vertex 0 too, so both fan from it and the
    # (non-planar) pair encloses zero volume instead of looking inside out
    return Mesh.from_polygons(V, [list(range(n)), [0, *range(n - 1, 0, -1)]])


def loop_sphere() -> Mesh:
    """The smallest sphere with an edge: one vertex, one self-loop, two one-gons."""
    p = Mesh.from_polygons(np.zeros((1, 3)), [[0]])
    m, _ = p.insert_edge(0, 0, 0, 0)
    return m


CLEAN = {
    **PLATONIC,
    "torus": lambda: topomesh.torus(12, 6),
    "genus3": lambda: topomesh.genus_surface(3),
}
DEGENERATE = {
    "dihedron3": lambda: dihedron(3),
    "dihedron5": lambda: dihedron(5),
    "loop_sphere": loop_sphere,
    "sierpinski": sierpinski_tetrahedron, "self_loop": self_loop_cube, "two_gon": two_gon_cube, "handle_loop": handle_loop_cube}
CORPUS = {**CLEAN, **DEGENERATE}


# ------------------------------------------------------------------ helpers


def assert_peers_agree(m: Mesh) -> None:
    """trimesh watertight/winding and manifold3d genus on the triangulation."""
    verts, tris, _ = m.triangulate()
    tm = trimesh.Trimesh(verts, tris, process=False)
    assert tm.is_watertight
    assert tm.is_winding_consistent
    mf = manifold3d.Manifold(
        manifold3d.Mesh(vert_properties=verts.astype(np.float32), tri_verts=tris.astype(np.uint32))
    )
    assert mf.status() == manifold3d.Error.NoError
    assert m.n_components == 1
    assert mf.genus() == m.genus


def assert_same_points(a: np.ndarray, b: np.ndarray, rtol: float) -> None:
    """Equal point sets up to order: every point has a partner within rtol·scale."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert a.shape == b.shape
    tol = rtol * max(1.0, np.abs(a).max())
    assert cKDTree(a).query(b)[0].max() <= tol
    assert cKDTree(b).query(a)[0].max() <= tol


def canonical_faces(verts: np.ndarray, faces, ref: np.ndarray) -> list[tuple[int, ...]]:
    """Faces renumbered onto the matching vertices of `ref`, each rotated to
    start at its smallest index (orientation kept), sorted."""
    d, idx = cKDTree(ref).query(verts)
    assert d.max() <= 1e-6 * max(1.0, np.abs(ref).max())
    out = []
    for f in faces:
        g = [int(idx[i]) for i in f]
        k = g.index(min(g))
        out.append(tuple(g[k:] + g[:k]))
    return sorted(out)


def valence_list(m: Mesh) -> Counter:
    return Counter(m.valence_histogram)


# --------------------------------------------------------- count formulas


def expected(name: str, m: Mesh) -> tuple[int, int, int, Counter]:
    """(V', E', F', face-size histogram) after one level of scheme `name`."""
    V, E, F = m.n_vertices, m.n_edges, m.n_faces
    H = 2 * E
    sizes = m.face_sizes
    f3 = int((sizes == 3).sum())
    ng = sizes[sizes != 3]
    fhist = Counter(m.face_size_histogram)
    vhist = Counter(m.valence_histogram)
    if name == "catmull_clark":
        return V + E + F, 4 * E, H, Counter({4: H})
    if name == "doo_sabin":
        return H, 2 * H, F + E + V, fhist + Counter({4: E}) + vhist
    if name == "loop":
        vt, et, ft = V + len(ng), E + int(ng.sum()), f3 + int(ng.sum())
        return vt + et, 2 * et + 3 * ft, 4 * ft, Counter({3: 4 * ft})
    if name == "sqrt3":
        return V + F, 3 * E, H, Counter({3: H})
    if name == "simplest":
        return E, H, F + V, fhist + vhist
    if name == "midpoint":
        return (
            V + E + len(ng),
            2 * E + 3 * f3 + int(ng.sum()),
            4 * f3 + int(ng.sum()),
            Counter({3: 4 * f3, 4: int(ng.sum())}) - Counter(),
        )
    if name == "dual":
        return F, E, V, vhist
    raise AssertionError(name)


def assert_follows_formulas(scheme: str, m: Mesh, r: Mesh) -> None:
    """``r`` (one level of ``scheme`` on ``m``) is valid and has the counts,
    face-size histogram, genus and components the scheme's formulas give."""
    r.validate()
    v, e, f, hist = expected(scheme, m)
    assert (r.n_vertices, r.n_edges, r.n_faces) == (v, e, f)
    assert Counter(r.face_size_histogram) == hist
    assert r.genus == m.genus
    assert r.n_components == m.n_components


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("mesh_name", list(CORPUS))
def test_counts_genus_validate(scheme: str, mesh_name: str) -> None:
    m = CORPUS[mesh_name]()
    r = getattr(m, scheme)()
    assert_follows_formulas(scheme, m, r)
    # a second level follows the formulas again, and iterations=2 is two levels
    r2 = getattr(m, scheme)(iterations=2)
    r2.validate()
    assert r2 == getattr(r, scheme)()
    v2, e2, f2, _ = expected(scheme, r)
    assert (r2.n_vertices, r2.n_edges, r2.n_faces) == (v2, e2, f2)
    assert r2.genus == m.genus


@pytest.mark.parametrize("scheme", SCHEMES)
def test_vertex_valences(scheme: str) -> None:
    m = topomesh.dodecahedron()
    r = getattr(m, scheme)()
    vh = Counter(r.valence_histogram)
    if scheme in ("doo_sabin", "simplest"):
        assert vh == Counter({4: r.n_vertices})
    elif scheme == "dual":
        assert vh == Counter(m.face_size_histogram)
    elif scheme == "catmull_clark":
        # old vertices keep valence 3, edge points 4, face points 5
        assert vh == Counter({3: 20, 4: 30, 5: 12})


def test_dodecahedron_face_histograms() -> None:
    m = topomesh.dodecahedron()
    assert m.doo_sabin().face_size_histogram == {3: 20, 4: 30, 5: 12}
    assert m.simplest().face_size_histogram == {3: 20, 5: 12}
    assert m.dual().face_size_histogram == {3: 20}
    assert m.sqrt3().face_size_histogram == {3: 60}


# --------------------------------------------------------- peer validation


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("mesh_name", list(CLEAN) + ["two_gon"])
def test_peers_accept_output(scheme: str, mesh_name: str) -> None:
    if mesh_name == "two_gon" and scheme == "loop":
        pytest.skip("Loop of a fanned two-gon has a multi-edge: peers index edges by vertex pair")
    m = CORPUS[mesh_name]()
    r = getattr(m, scheme)()
    assert_peers_agree(r)


def test_sierpinski_corpus_mesh() -> None:
    s = sierpinski_tetrahedron()
    s.validate()
    assert (s.n_vertices, s.n_edges, s.n_faces, s.genus, s.n_self_loops) == (10, 30, 16, 3, 6)
    assert s.face_size_histogram == {3: 12, 6: 4}


@pytest.mark.parametrize("scheme", ["catmull_clark", "doo_sabin", "loop"])
def test_sierpinski_loops_open_into_tubes(scheme: str) -> None:
    """Zero-length self-loops (Sierpinski paper Fig. 7, 11-14): one level
    gives every loop's two sides distinct new points (no two output points
    coincide); from level 2 on, the peers see a genus-3 surface. (At level 1
    the cut loop is a double edge and the tube's cross-section face is not
    flat, which vertex-indexed peers cannot triangulate.)"""
    m = sierpinski_tetrahedron()
    r = getattr(m, scheme)()
    d, _ = cKDTree(r.vertices).query(r.vertices, k=2)
    assert d[:, 1].min() > 1e-3
    assert r.n_self_loops == 0
    r2 = getattr(r, scheme)()
    r2.validate()
    assert r2.genus == 3
    assert_peers_agree(r2)


@pytest.mark.parametrize("scheme", ["catmull_clark", "doo_sabin", "loop"])
def test_handle_loop_opens_after_two_levels(scheme: str) -> None:
    """A zero-length loop with the same (merged) face on both sides."""
    m = handle_loop_cube()
    assert m.genus == 1 and m.n_self_loops == 1
    r = getattr(m, scheme)(iterations=2)
    r.validate()
    assert r.n_self_loops == 0
    assert_peers_agree(r)


def test_doo_sabin_opens_one_gon() -> None:
    m = self_loop_cube()
    for k in (1, 2):
        r = m.doo_sabin(iterations=k)
        d, _ = cKDTree(r.vertices).query(r.vertices, k=2)
        assert d[:, 1].min() > 1e-4
        assert_peers_agree(r)


def test_doo_sabin_self_loop_sides_get_distinct_points() -> None:
    m = handle_loop_cube()
    r = m.doo_sabin()
    d, _ = cKDTree(r.vertices).query(r.vertices, k=2)
    assert d[:, 1].min() > 1e-4


# ------------------------------------------------------ independent rules


def edge_faces(F):
    """{(min, max): [faces]} for meshes without multi-edges or self-loops."""
    out: dict[tuple[int, int], list[int]] = {}
    for i, f in enumerate(F):
        for k in range(len(f)):
            a, b = f[k], f[(k + 1) % len(f)]
            out.setdefault((min(a, b), max(a, b)), []).append(i)
    return out


def ref_catmull_clark(V, F):
    fp = np.array([V[f].mean(0) for f in F])
    ef = edge_faces(F)
    ep = np.array([(V[a] + V[b] + fp[f1] + fp[f2]) / 4 for (a, b), (f1, f2) in ef.items()])
    n = np.zeros(len(V))
    R = np.zeros_like(V)
    Q = np.zeros_like(V)
    nq = np.zeros(len(V))
    for a, b in ef:
        mid = (V[a] + V[b]) / 2
        R[a] += mid
        R[b] += mid
        n[a] += 1
        n[b] += 1
    for i, f in enumerate(F):
        for v in f:
            Q[v] += fp[i]
            nq[v] += 1
    Q /= nq[:, None]
    R /= n[:, None]
    vp = (Q + 2 * R + (n[:, None] - 3) * V) / n[:, None]
    return np.vstack([vp, ep, fp])


def ref_doo_sabin(V, F):
    out = []
    for f in F:
        n = len(f)
        for k in range(n):
            p = np.zeros(3)
            for i in range(n):
                j = (i - k) % n
                a = (3 + 2 * np.cos(2 * np.pi * j / n)) / (4 * n) + (0.25 if j == 0 else 0.0)
                p += a * V[f[i]]
            out.append(p)
    return np.array(out)


def ref_sqrt3(V, F):
    """Kobbelt's rule; returns (points, triangles over those points)."""
    ef = edge_faces(F)
    nb = [[] for _ in V]
    for a, b in ef:
        nb[a].append(b)
        nb[b].append(a)
    vp = []
    for v, ns in enumerate(nb):
        n = len(ns)
        al = (4 - 2 * np.cos(2 * np.pi / n)) / 9
        vp.append((1 - al) * V[v] + al / n * V[ns].sum(0))
    c = np.array([V[f].mean(0) for f in F])
    pts = np.vstack([vp, c])
    nv = len(V)
    side = {}
    for i, f in enumerate(F):
        for k in range(len(f)):
            side[(f[k], f[(k + 1) % len(f)])] = i
    tris = [(a, nv + side[(b, a)], nv + fi) for (a, b), fi in side.items()]
    return pts, tris


def fan_triangulate(V, F):
    """Every non-triangle fanned around its centroid (topomesh's extended Loop)."""
    V = list(V)
    T = []
    for f in F:
        if len(f) == 3:
            T.append(f)
            continue
        c = len(V)
        V.append(np.mean([V[i] for i in f], axis=0))
        T += [[f[k], f[(k + 1) % len(f)], c] for k in range(len(f))]
    return np.array(V), np.array(T)


TRI = ["tetrahedron", "octahedron", "icosahedron"]
POLY = ["cube", "dodecahedron", "torus", "genus3"]


@pytest.mark.parametrize("mesh_name", TRI + ["icosphere"])
def test_loop_matches_trimesh(mesh_name: str) -> None:
    if mesh_name == "icosphere":
        s = trimesh.creation.icosphere(3)
        m = Mesh.from_polygons(s.vertices, s.faces)
    else:
        m = CLEAN[mesh_name]()
    for k in (1, 2):
        v, f = trimesh.remesh.subdivide_loop(m.vertices, m.triangles(), iterations=k)
        r = m.loop(iterations=k)
        assert_same_points(r.vertices, v, 1e-9)
        assert canonical_faces(v, f, r.vertices) == canonical_faces(r.vertices, r.triangles(), r.vertices)


@pytest.mark.parametrize("mesh_name", POLY)
def test_extended_loop_is_loop_of_centroid_fan(mesh_name: str) -> None:
    m = CLEAN[mesh_name]()
    fv, ft = fan_triangulate(m.vertices, faces_of(m))
    v, f = trimesh.remesh.subdivide_loop(fv, ft)
    r = m.loop()
    assert_same_points(r.vertices, v, 1e-9)
    assert canonical_faces(v, f, r.vertices) == canonical_faces(r.vertices, r.triangles(), r.vertices)


@pytest.mark.parametrize("mesh_name", TRI + ["icosphere"])
def test_midpoint_matches_trimesh(mesh_name: str) -> None:
    if mesh_name == "icosphere":
        s = trimesh.creation.icosphere(2)
        m = Mesh.from_polygons(s.vertices, s.faces)
    else:
        m = CLEAN[mesh_name]()
    v, f = trimesh.remesh.subdivide(m.vertices, m.triangles())
    r = m.midpoint()
    assert_same_points(r.vertices, v, 1e-9)
    assert canonical_faces(v, f, r.vertices) == canonical_faces(r.vertices, r.triangles(), r.vertices)


@pytest.mark.parametrize("mesh_name", POLY)
def test_midpoint_on_polygons(mesh_name: str) -> None:
    m = CLEAN[mesh_name]()
    F = faces_of(m)
    V = m.vertices
    ef = edge_faces(F)
    want = np.vstack(
        [V, [(V[a] + V[b]) / 2 for a, b in ef]] + [V[f].mean(0)[None] for f in F if len(f) != 3]
    )
    assert_same_points(m.midpoint().vertices, want, 1e-9)


@pytest.mark.parametrize("mesh_name", list(CLEAN))
def test_catmull_clark_matches_reference(mesh_name: str) -> None:
    m = CLEAN[mesh_name]()
    assert_same_points(m.catmull_clark().vertices, ref_catmull_clark(m.vertices, faces_of(m)), 1e-9)


@pytest.mark.skipif(importlib.util.find_spec("pyOpenSubdiv") is None, reason="pyOpenSubdiv not installed")
@pytest.mark.parametrize("mesh_name", list(CLEAN))
def test_catmull_clark_matches_opensubdiv(mesh_name: str) -> None:
    from pyOpenSubdiv.pysubdivision import pysubdivide

    m = CLEAN[mesh_name]()
    for k in (1, 2):
        out = pysubdivide(k, m.vertices.tolist(), [], m.face_indices.tolist(), m.face_sizes.tolist())
        v = np.array(out["vertices"])
        r = m.catmull_clark(iterations=k)
        assert_same_points(r.vertices, v, 1e-6)  # OpenSubdiv here computes in float32
        assert canonical_faces(v, out["faces"], r.vertices) == canonical_faces(r.vertices, faces_of(r), r.vertices)


@pytest.mark.parametrize("mesh_name", list(CLEAN))
def test_doo_sabin_matches_reference(mesh_name: str) -> None:
    m = CLEAN[mesh_name]()
    assert_same_points(m.doo_sabin().vertices, ref_doo_sabin(m.vertices, faces_of(m)), 1e-9)


def pymeshlab_run(m: Mesh, filt: str):
    pml = pytest.importorskip("pymeshlab")
    ms = pml.MeshSet()
    ms.add_mesh(pml.Mesh(m.vertices, [np.asarray(f, dtype=np.uint32) for f in faces_of(m)]))
    kw = {"threshold": pml.PercentageValue(0.0)} if filt.endswith("loop") else {}
    getattr(ms, filt)(iterations=1, **kw)
    return ms.current_mesh().vertex_matrix()


@pytest.mark.parametrize("mesh_name", list(PLATONIC))
def test_doo_sabin_matches_pymeshlab(mesh_name: str) -> None:
    m = CLEAN[mesh_name]()
    v = pymeshlab_run(m, "meshing_surface_subdivision_doo_sabin")
    assert_same_points(m.doo_sabin().vertices, v, 1e-6)  # pymeshlab computes in float32


@pytest.mark.parametrize("mesh_name", TRI)
def test_loop_matches_pymeshlab(mesh_name: str) -> None:
    m = CLEAN[mesh_name]()
    v = pymeshlab_run(m, "meshing_surface_subdivision_loop")
    assert_same_points(m.loop().vertices, v, 1e-6)


@pytest.mark.parametrize("mesh_name", list(CLEAN))
def test_sqrt3_matches_reference(mesh_name: str) -> None:
    m = CLEAN[mesh_name]()
    pts, tris = ref_sqrt3(m.vertices, faces_of(m))
    r = m.sqrt3()
    assert_same_points(r.vertices, pts, 1e-9)
    assert canonical_faces(pts, tris, r.vertices) == canonical_faces(r.vertices, faces_of(r), r.vertices)
    # two levels on triangles: Kobbelt's triadic split, 9x the faces
    if mesh_name in TRI:
        assert m.sqrt3(iterations=2).n_faces == 9 * m.n_faces
    # the second level of one call consumes the first (issue 19): the same
    # mesh, bit for bit, as a call per level (closed inputs: no parity)
    two, once = m.sqrt3(iterations=2), r.sqrt3()
    assert np.array_equal(two.vertices, once.vertices)
    assert np.array_equal(two.face_indices, once.face_indices)
    assert np.array_equal(two.corner_twins, once.corner_twins)


@pytest.mark.parametrize("mesh_name", list(CLEAN))
def test_simplest_and_dual_positions(mesh_name: str) -> None:
    m = CLEAN[mesh_name]()
    F = faces_of(m)
    V = m.vertices
    mids = np.array([(V[a] + V[b]) / 2 for a, b in edge_faces(F)])
    assert_same_points(m.simplest().vertices, mids, 1e-9)
    # the second level of one call consumes the first (issue 19): the same
    # mesh, bit for bit, as a call per level
    for name in ("simplest", "honeycomb", "vertex_truncation", "dual"):
        two, once = getattr(m, name)(iterations=2), getattr(getattr(m, name)(), name)()
        assert np.array_equal(two.vertices, once.vertices), name
        assert np.array_equal(two.face_indices, once.face_indices), name
        assert np.array_equal(two.corner_twins, once.corner_twins), name
    assert_same_points(m.dual().vertices, np.array([V[f].mean(0) for f in F]), 1e-9)
    # the dual keeps orientation: positive volume for convex solids
    if mesh_name in PLATONIC:
        assert m.dual().volume > 0
        assert m.dual(iterations=2).face_size_histogram == m.face_size_histogram


# ---------------------------------------------------------------- API


@pytest.mark.parametrize("scheme", SCHEMES)
def test_iterations_argument(scheme: str) -> None:
    m = topomesh.cube()
    with pytest.raises(MeshError):
        getattr(m, scheme)(iterations=-1)
    assert getattr(m, scheme)(iterations=0) == m
    r = getattr(m, scheme)(iterations=1, progress=True)
    assert r == getattr(m, scheme)()


def test_point_sphere_carried_through() -> None:
    m, _, _ = topomesh.tetrahedron().create_vertex([5.0, 0.0, 0.0])
    for s in SCHEMES:
        r = getattr(m, s)()
        r.validate()
        assert r.n_components == 2
        assert np.any(np.all(r.vertices == [5.0, 0.0, 0.0], axis=1))


# ------------------------------------------------------ random degenerate meshes

from hypothesis import given, settings, strategies as st  # noqa: E402


@st.composite
def random_mesh(draw) -> Mesh:
    """A Platonic solid after a few random InsertEdge calls: self-loops,
    multi-edges, one-gons, two-gons, handles and repeated vertices."""
    m = draw(st.sampled_from([topomesh.tetrahedron, topomesh.cube, topomesh.octahedron]))()
    for _ in range(draw(st.integers(0, 6))):
        sizes = m.face_sizes
        f1 = draw(st.integers(0, len(sizes) - 1))
        f2 = draw(st.integers(0, len(sizes) - 1))
        p1 = draw(st.integers(0, int(sizes[f1]) - 1))
        p2 = draw(st.integers(0, int(sizes[f2]) - 1))
        m, _ = m.insert_edge(f1, p1, f2, p2)
    return m


@settings(max_examples=60, deadline=None)
@given(random_mesh(), st.sampled_from(SCHEMES))
def test_random_meshes_follow_formulas(m: Mesh, scheme: str) -> None:
    m.validate()
    r = getattr(m, scheme)()
    assert_follows_formulas(scheme, m, r)
    assert np.isfinite(r.vertices).all()


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("mesh_name", list(CLEAN))
def test_orientation_kept(scheme: str, mesh_name: str) -> None:
    """Outward faces stay outward: the signed volume stays positive (and, for
    these convex or smooth inputs, does not grow)."""
    m = CLEAN[mesh_name]()
    r = getattr(m, scheme)()
    assert m.volume > 0
    assert 0 < r.volume < 1.0 * m.volume + 1e-9
