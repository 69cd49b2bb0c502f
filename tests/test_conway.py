"""Conway's polyhedron operators: topomesh.conway, Mesh.conway, the operator
methods and Mesh.canonicalize (src/schemes/conway, docs/schemes/conway.md).

Counts of named polyhedra come from Hart's "Conway Notation for Polyhedra"
and the standard tables of Archimedean and Catalan solids; the per-operator
formulas are checked against the table ``topomesh.conway_operators()``
states, on inputs of every genus and with self-loops and two-gons.
"""

from __future__ import annotations

import numpy as np
import pytest

import topomesh
from topomesh import MeshError
from tests.harness import assert_agrees_with_peers


# (notation, V, E, F) of named polyhedra
NAMED = [
    ("T", 4, 6, 4), ("C", 8, 12, 6), ("O", 6, 12, 8), ("D", 20, 30, 12), ("I", 12, 30, 20),
    ("aT", 6, 12, 8),  # octahedron
    ("aC", 12, 24, 14),  # cuboctahedron
    ("aD", 30, 60, 32),  # icosidodecahedron
    ("tT", 12, 18, 8), ("tC", 24, 36, 14), ("tO", 24, 36, 14), ("tD", 60, 90, 32),
    ("tI", 60, 90, 32),  # truncated icosahedron
    ("kT", 8, 18, 12), ("kC", 14, 36, 24), ("kO", 14, 36, 24), ("kI", 32, 90, 60),
    ("kD", 32, 90, 60),  # pentakis dodecahedron
    ("jC", 14, 24, 12),  # rhombic dodecahedron
    ("jD", 32, 60, 30),  # rhombic triacontahedron
    ("eC", 24, 48, 26),  # rhombicuboctahedron
    ("eI", 60, 120, 62),  # rhombicosidodecahedron
    ("oC", 26, 48, 24),  # deltoidal icositetrahedron
    ("oD", 62, 120, 60),  # deltoidal hexecontahedron
    ("bO", 48, 72, 26),  # truncated cuboctahedron
    ("bD", 120, 180, 62),  # truncated icosidodecahedron
    ("mC", 26, 72, 48),  # disdyakis dodecahedron
    ("mD", 62, 180, 120),  # disdyakis triacontahedron
    ("sC", 24, 60, 38),  # snub cube
    ("sD", 60, 150, 92),  # snub dodecahedron
    ("gC", 38, 60, 24),  # pentagonal icositetrahedron
    ("gD", 92, 150, 60),  # pentagonal hexecontahedron
    ("sT", 12, 30, 20),  # icosahedron
    ("gT", 20, 30, 12),  # dodecahedron
    ("nC", 14, 36, 24), ("zD", 60, 90, 32),
    ("cC", 32, 48, 18),  # chamfered cube
    ("cD", 80, 120, 42),  # chamfered dodecahedron
    ("uT", 10, 24, 16), ("pC", 32, 60, 30), ("wT", 28, 42, 16), ("qC", 44, 72, 30), ("lC", 32, 60, 30),
    ("P5", 10, 15, 7), ("A5", 10, 20, 12), ("Y5", 6, 10, 6),
    ("dA5", 12, 20, 10),  # pentagonal trapezohedron
    ("dtkC", 38, 108, 72), ("t5dD", 60, 90, 32), ("k5aD", 42, 120, 80), ("dP6", 8, 18, 12),
]


@pytest.mark.parametrize("notation,v,e,f", NAMED, ids=[n[0] for n in NAMED])
def test_named_polyhedra(notation, v, e, f):
    m = topomesh.conway(notation)
    m.validate()
    assert (m.n_vertices, m.n_edges, m.n_faces) == (v, e, f)
    assert m.genus == 0 and m.volume > 0


@pytest.mark.parametrize(
    "notation,hist",
    [
        ("tI", {5: 12, 6: 20}),
        ("aC", {3: 8, 4: 6}),
        ("sC", {3: 32, 4: 6}),
        ("gD", {5: 60}),
        ("bO", {4: 12, 6: 8, 8: 6}),
        ("eI", {3: 20, 4: 30, 5: 12}),
        ("mC", {3: 48}),
        ("kD", {3: 60}),
        ("cC", {4: 6, 6: 12}),
        ("t4dC", {4: 6, 6: 8}),  # dC is the octahedron: t4 truncates all its vertices (tO)
    ],
)
def test_face_size_histograms(notation, hist):
    assert topomesh.conway(notation).face_size_histogram == hist


def two_gon_cube() -> topomesh.Mesh:
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 1)
    assert m.face_size_histogram == {2: 1, 4: 6}
    return m


def self_loop_cube() -> topomesh.Mesh:
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 0)
    assert m.n_self_loops == 1
    return m


INPUTS = {
    "cube": topomesh.cube,
    "torus": lambda: topomesh.torus(6, 4),
    "genus2": lambda: topomesh.genus_surface(2),
    "two_gon": two_gon_cube,
    "self_loop": self_loop_cube,
}
OPS = topomesh.conway_operators()


def formula(s: str, v: int, e: int, f: int) -> int:
    """Evaluates a count formula of the operator table, e.g. ``"F + V + 2E"``."""
    total = 0
    for term in s.split("+"):
        term = term.strip()
        k, x = (int(term[:-1]), term[-1]) if len(term) > 1 else (1, term)
        total += k * {"V": v, "E": e, "F": f}[x]
    return total


@pytest.mark.parametrize("name", INPUTS)
@pytest.mark.parametrize("op", OPS, ids=[o["letter"] for o in OPS])
def test_operator_formulas_keep_genus(name, op):
    m = INPUTS[name]()
    before = (m.vertices.copy(), m.face_indices.copy())
    r = getattr(m, op["method"])()
    r.validate()
    want = tuple(formula(s, m.n_vertices, m.n_edges, m.n_faces) for s in op["counts"])
    assert (r.n_vertices, r.n_edges, r.n_faces) == want
    assert (r.euler_characteristic, r.genus, r.n_components) == (m.euler_characteristic, m.genus, m.n_components)
    # the method is the letter, and the input is untouched
    same = m.conway(op["letter"])
    assert np.array_equal(same.face_indices, r.face_indices) and np.allclose(same.vertices, r.vertices)
    assert np.array_equal(before[0], m.vertices) and np.array_equal(before[1], m.face_indices)


# operators built in one pass instead of through their definitions (issue 16)
ONE_PASS = {"j": "da", "o": "daa", "e": "aa", "m": "kj", "n": "kd", "z": "dk", "t": "dkd", "b": "dkda", "s": "dg", "v": "dwd"}


@pytest.mark.parametrize("name", INPUTS)
@pytest.mark.parametrize("letter", sorted(ONE_PASS))
def test_one_pass_operators_are_their_definitions(name, letter):
    """The one-pass build gives, bit for bit, what the definition's letters
    give applied one call at a time."""
    m = INPUTS[name]()
    r, d = m.conway(letter), m
    for c in reversed(ONE_PASS[letter]):
        d = d.conway(c)
    assert np.array_equal(r.face_sizes, d.face_sizes) and np.array_equal(r.face_indices, d.face_indices)
    assert np.array_equal(r.vertices, d.vertices)


@pytest.mark.parametrize("seed", ["T", "C", "D", "P5", "A4", "Y4"])
@pytest.mark.parametrize("op", OPS, ids=[o["letter"] for o in OPS])
def test_outputs_are_watertight(seed, op):
    """trimesh and manifold3d agree on every operator's output on a few seeds."""
    r = topomesh.conway(op["letter"] + seed)
    rep = assert_agrees_with_peers(r, expect_genus=0, planar=False)
    assert rep["trimesh_watertight"]


@pytest.mark.parametrize("name", ["torus", "genus2"])
@pytest.mark.parametrize("letter", ["a", "t", "k", "g", "s", "c", "w", "p", "q", "l", "u"])
def test_watertight_on_higher_genus(name, letter):
    import trimesh

    r = INPUTS[name]().conway(letter)
    verts, tris, _ = r.triangulate()
    tm = trimesh.Trimesh(vertices=verts, faces=tris, process=False)
    assert tm.is_watertight and tm.is_winding_consistent
    assert tm.euler_number == r.euler_characteristic


def test_numbered_operators():
    i = topomesh.icosahedron()
    # every icosahedron vertex is 5-valent, none 3-valent
    assert np.array_equal(i.truncate(5).face_indices, i.truncate().face_indices)
    assert i.truncate(3).n_faces == i.n_faces
    aD = topomesh.conway("aD")  # 20 triangles, 12 pentagons
    assert aD.kis(5).face_size_histogram == {3: 20 + 60}
    assert aD.kis(3).face_size_histogram == {3: 60, 5: 12}
    assert aD.loft(3).face_size_histogram == {3: 20, 4: 60, 5: 12}
    assert topomesh.conway("k3aD").n_faces == aD.kis(3).n_faces
    z = aD.zip(5)  # the dual of k5: its 12 pentagons raised
    assert (z.n_vertices, z.n_edges, z.n_faces) == (80, 120, 42)
    # every aD vertex is 4-valent: n4 is n
    assert np.array_equal(aD.needle(4).face_indices, aD.needle().face_indices)
    assert aD.needle(3).n_faces == aD.n_vertices
    for bad in (0, -1, 2**70):
        with pytest.raises(MeshError, match="n"):
            aD.kis(bad)


def test_dual_is_mesh_dual():
    for m in (topomesh.dodecahedron(), two_gon_cube(), self_loop_cube(), topomesh.genus_surface(2)):
        a, b = m.conway("d"), m.dual()
        assert np.array_equal(a.face_indices, b.face_indices) and np.allclose(a.vertices, b.vertices)


def oriented_faces(m: topomesh.Mesh) -> list:
    """Faces as cycles of rounded positions from their least corner (rotation
    only, so orientation counts), sorted."""
    p = np.round(m.vertices, 9) + 0.0
    out, at = [], 0
    for s in m.face_sizes:
        cyc = [tuple(p[v]) for v in m.face_indices[at : at + s]]
        at += s
        k = cyc.index(min(cyc))
        out.append(cyc[k:] + cyc[:k])
    return sorted(out)


@pytest.mark.parametrize("method", ["gyro", "snub", "whirl", "propellor", "volute"])
def test_chirality(method):
    """The chiral operators turn the way the orientation says, the same on
    every face of every genus: the cube is its own mirror image (r C is C
    with other vertex ids), so g r C is g C; the mirror image r g C is the
    other hand; orientation stays outward."""
    c = topomesh.cube()
    g = getattr(c, method)()
    assert oriented_faces(getattr(c.reflect(), method)()) == oriented_faces(g)
    assert oriented_faces(g.reflect()) != oriented_faces(g)
    assert g.volume > 0 and g.reflect().volume > 0
    g2 = getattr(topomesh.genus_surface(2), method)()
    g2.validate()
    assert g2.genus == 2
    assert oriented_faces(g2.reflect().reflect()) == oriented_faces(g2)


def test_gyro_turns_one_way_on_genus_2():
    """Each gyro pentagon lies on the same side of its diagonal from the face
    centre to the input vertex, seen from outside, all over a genus-2 surface."""
    m = topomesh.genus_surface(2)
    g = m.gyro()
    nv, nf = m.n_vertices, m.n_faces  # output: input vertices, then face centres
    p, at, signs = g.vertices, 0, []
    normals = g.face_normals
    for k, s in enumerate(g.face_sizes):
        vs = g.face_indices[at : at + s]
        at += s
        c = p[next(v for v in vs if nv <= v < nv + nf)]
        v = p[next(v for v in vs if v < nv)]
        signs.append(np.sign(normals[k] @ np.cross(v - c, p[vs].mean(axis=0) - c)))
    assert len(set(signs)) == 1 and signs[0] != 0


@pytest.mark.parametrize(
    "notation,pattern",
    [
        ("dxC", r'position 1 of "dxC": unknown letter \'x\''),
        ("d C", r"position 1 .* unexpected character ' '"),
        ("5C", r"position 0 .* number '5' without a letter"),
        ("Ct", r"position 0 .* seed 'C' must be the rightmost"),
        ("a3C", r"position 0 .* operator 'a' takes no number"),
        ("P", r"seed 'P' needs its number of sides"),
        ("A2", r"at least 3 sides"),
        ("t0C", r"position 1 .* number 0 after 't'"),
        ("tk", r"no seed"),
        ("", r"no seed"),
    ],
)
def test_parse_errors(notation, pattern):
    with pytest.raises(MeshError, match=pattern):
        topomesh.conway(notation)


def test_seed_mesh():
    c = topomesh.cube()
    assert np.array_equal(topomesh.conway("tk", c).face_indices, topomesh.conway("tkC").face_indices)
    assert np.array_equal(topomesh.conway("tk", seed=c).face_indices, c.conway("tk").face_indices)
    with pytest.raises(MeshError, match="seed mesh was given too"):
        topomesh.conway("tkC", c)
    with pytest.raises(MeshError, match="seed mesh was given too"):
        c.conway("tkC")
    assert np.array_equal(c.conway("").face_indices, c.face_indices)


def test_open_meshes_are_refused():
    open_cube = topomesh.Mesh.from_polygons(topomesh.cube().vertices, topomesh.cube().face_indices.reshape(6, 4)[1:])
    assert open_cube.n_boundary_loops == 1
    for op in OPS:
        # named after the call, not the step inside it that refused (truncate's dual, zip's kis)
        call = f'conway "{op["letter"]}"'
        with pytest.raises(MeshError, match=rf"^{call}: the mesh has 1 boundary loop \(it is open\); "
                                            rf"{call} takes closed meshes only: it has no boundary rule"):
            open_cube.conway(op["letter"])
        if op["method"] != "dual":  # Mesh.dual keeps boundaries (Blender's convention)
            with pytest.raises(MeshError, match=rf"^{op['method']}: the mesh has 1 boundary loop \(it is open\)"):
                getattr(open_cube, op["method"])()
    with pytest.raises(MeshError, match="boundary loop"):
        open_cube.canonicalize()


def test_memory_budget():
    try:
        topomesh.set_memory_budget(1 << 20)
        with pytest.raises(MeshError, match="budget"):
            topomesh.conway("kkkkkkkkD")
    finally:
        topomesh.set_memory_budget(None)
    with pytest.raises(MeshError, match="31-bit"):
        topomesh.conway("k" * 40 + "C")


@pytest.mark.parametrize("notation", ["C", "tI", "dtkC", "gC", "A5", "kD"])
def test_canonicalize(notation):
    m = topomesh.conway(notation)
    r0 = m.canonicalize(iterations=0)[1]
    c, r = m.canonicalize(iterations=3000, tol=1e-13)
    assert isinstance(c, topomesh.Mesh) and isinstance(r, float)
    assert r < 1e-6 and r <= r0
    assert np.array_equal(c.face_indices, m.face_indices)  # only positions move
    # every edge line tangent to the unit sphere, faces planar
    a, b = c.vertices[c.edges[:, 0]], c.vertices[c.edges[:, 1]]
    d = b - a
    t = a - d * (np.einsum("ij,ij->i", d, a) / np.einsum("ij,ij->i", d, d))[:, None]
    assert np.allclose(np.linalg.norm(t, axis=1), 1.0, atol=1e-5)
    for bad in (-1.0, 2.0, float("nan")):
        with pytest.raises(MeshError, match="tol"):
            m.canonicalize(tol=bad)
    with pytest.raises(MeshError, match="iterations"):
        m.canonicalize(iterations=-1)


def test_operator_table():
    letters = "".join(o["letter"] for o in OPS)
    assert set(letters) >= set("datkjeogsbmnzcuwpqlr")
    for o in OPS:
        assert callable(getattr(topomesh.Mesh, o["method"]))
        assert o["takes_n"] == (o["letter"] in "tknzl")


from hypothesis import given, settings, strategies as st  # noqa: E402

SMALL = {"T": topomesh.tetrahedron, "C": topomesh.cube, "P3": lambda: topomesh.conway("P3"), "torus": lambda: topomesh.torus(4, 3), "self_loop": self_loop_cube, "two_gon": two_gon_cube}


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(sorted(SMALL)), st.lists(st.sampled_from([o["letter"] for o in OPS]), min_size=1, max_size=3))
def test_random_chains_follow_the_table(seed, letters):
    """A random chain of operators: the counts follow the table step by step
    (applied right to left), and χ, genus and components are kept."""
    m = SMALL[seed]()
    v, e, f = m.n_vertices, m.n_edges, m.n_faces
    table = {o["letter"]: o["counts"] for o in OPS}
    for letter in reversed(letters):
        v, e, f = (formula(s, v, e, f) for s in table[letter])
    r = m.conway("".join(letters))
    r.validate()
    assert (r.n_vertices, r.n_edges, r.n_faces) == (v, e, f)
    assert (r.euler_characteristic, r.genus, r.n_components) == (m.euler_characteristic, m.genus, m.n_components)


def test_big_seed_is_checked_against_the_budget():
    try:
        topomesh.set_memory_budget(1 << 20)
        with pytest.raises(MeshError, match="budget"):
            topomesh.conway("P1000000")
    finally:
        topomesh.set_memory_budget(None)
