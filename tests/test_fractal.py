"""Fractal schemes: Mesh.sierpinski and topomesh.menger_sponge.

Count formulas are recomputed here from the closed forms of the module docs
(src/schemes/sierpinski.rs, src/schemes/menger_sponge.rs) and compared with
the meshes produced.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import topomesh
from tests.harness import PLATONIC, assert_agrees_with_peers



def cube_with_two_gon() -> topomesh.Mesh:
    """The cube with an edge doubled: one two-gon and a multi-edge."""
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 1)
    assert m.face_size_histogram == {2: 1, 4: 6}
    return m


def cube_with_self_loop() -> topomesh.Mesh:
    """The cube with a self-loop bounding a one-gon inside a face."""
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 0)
    assert m.n_self_loops == 1 and m.face_size_histogram == {1: 1, 4: 5, 5: 1}
    return m


INPUTS = {
    **{k: f for k, f in PLATONIC.items()},
    "torus": lambda: topomesh.torus(6, 4),
    "genus3": lambda: topomesh.genus_surface(3),
    "two_gon": cube_with_two_gon,
    "self_loop": cube_with_self_loop,
}


def expected_counts(m: topomesh.Mesh, n: int) -> dict:
    """Closed forms after n >= 1 iterations for inputs whose vertices each
    have one cone (K = V) and whose all-loop faces are one-gons (F0 = #one-gons)."""
    v, e, loops = m.n_vertices, m.n_edges, m.n_self_loops
    k, f0 = v, m.face_size_histogram.get(1, 0)
    big_n = e - loops
    s = (4**n - 1) // 3
    chi = v - e + k + f0 - big_n * s
    return {
        "V": v + big_n * s,
        "E": e + 4 * big_n * s,
        "F": k + f0 + 2 * big_n * s,
        "loops": loops + big_n * s,
        "genus": m.n_components - chi // 2,
    }


@pytest.mark.parametrize("name", list(INPUTS))
def test_sierpinski_counts_six_iterations(name):
    m0 = INPUTS[name]()
    m = m0
    for n in range(1, 7):
        m = m.sierpinski()
        m.validate()
        got = {"V": m.n_vertices, "E": m.n_edges, "F": m.n_faces, "loops": m.n_self_loops, "genus": m.genus}
        assert got == expected_counts(m0, n), f"{name}, iteration {n}"
        assert m.n_components == 1
    assert m0.sierpinski(6) == m


def test_sierpinski_tetrahedron_anchor():
    t = topomesh.tetrahedron()
    assert [t.sierpinski(k).genus for k in (1, 2, 3)] == [3, 15, 63]
    # 4^3 tetrahedra, each face a triangle carrying self-loops
    s = t.sierpinski(3)
    assert s.n_faces == 4 * 64
    assert set(s.face_size_histogram) == {3, 4, 6}  # corner triangles with 0 or 1 loop, back hexagons


def test_sierpinski_keeps_old_vertices_and_adds_midpoints():
    c = topomesh.cube()
    s = c.sierpinski()
    np.testing.assert_array_equal(s.vertices[:8], c.vertices)
    mids = 0.5 * (c.vertices[c.edges[:, 0]] + c.vertices[c.edges[:, 1]])
    np.testing.assert_allclose(s.vertices[8:], mids)
    # zero-length self-loops: one at each midpoint
    loops = s.edges[s.edges[:, 0] == s.edges[:, 1], 0]
    assert sorted(loops.tolist()) == list(range(8, 20))


def test_sierpinski_deformed_cube_and_zero_iterations():
    c = topomesh.cube()
    rng = np.random.default_rng(1)
    d = c.with_vertices(c.vertices + 0.2 * rng.standard_normal(c.vertices.shape))
    s = d.sierpinski(4)
    s.validate()
    assert s.genus == topomesh.cube().sierpinski(4).genus
    assert c.sierpinski(0) == c


def test_sierpinski_progress_bar(capsys):
    s = topomesh.octahedron().sierpinski(2, progress=True)
    assert s == topomesh.octahedron().sierpinski(2)
    assert "sierpinski" in capsys.readouterr().err


# --- geometric realization: smoothing opens the zero-length self-loops
#
# One step is not enough: Catmull-Clark turns each self-loop into two edges
# between the same two points (its vertex point and its edge point), and
# Doo-Sabin likewise, so the tube still has no cross-section there and the
# peers (which name edges by vertex pairs) see four faces on one edge. Two
# steps open every tube. Doo-Sabin faces are not planar, so for it the
# volume comparison of the harness is left out.


def _smoothers():
    return ["doo_sabin", "catmull_clark"]



@pytest.mark.parametrize("smoother", _smoothers())
@pytest.mark.parametrize("name", list(PLATONIC))
@pytest.mark.parametrize("k", [1, 2, 3])
def test_sierpinski_smoothed_agrees_with_peers(name, k, smoother):
    s = PLATONIC[name]().sierpinski(k)
    smooth = getattr(s, smoother)(2)
    assert smooth.genus == s.genus
    if smoother == "catmull_clark":
        assert_agrees_with_peers(smooth, expect_genus=s.genus)
    else:
        assert_agrees_with_peers(smooth, expect_genus=s.genus, planar=False)


def test_one_smoothing_step_leaves_loops_closed():
    """After one Catmull-Clark step every self-loop is a pair of edges
    between the same two vertices (a zero-width tube)."""
    s = topomesh.tetrahedron().sierpinski(1)
    one = s.catmull_clark(1)
    pairs = np.sort(one.edges, axis=1)
    _, counts = np.unique(pairs, axis=0, return_counts=True)
    assert (counts == 2).sum() == s.n_self_loops


# --- classic Menger sponge


def sponge_genus(n: int) -> int:
    """1 − χ(solid) with χ(S_n) = 20 χ(S_{n−1}) − 24 χ(carpet_{n−1}), χ(S_0) = 1
    (inclusion–exclusion over the 20 blocks; see src/schemes/menger_sponge.rs)."""
    chi = 1
    for m in range(1, n + 1):
        carpet = 1 - (8 ** (m - 1) - 1) // 7
        chi = 20 * chi - 24 * carpet
    return 1 - chi


def test_sponge_genus_recurrence_matches_closed_form():
    assert [sponge_genus(n) for n in range(5)] == [0, 5, 81, 1409, 26433]
    for n in range(8):
        assert sponge_genus(n) * 133 == 21 * 20**n + 38 * 8**n - 59


@pytest.mark.parametrize("level", [0, 1, 2, 3])
def test_menger_sponge_agrees_with_peers(level):
    m = topomesh.menger_sponge(level)
    m.validate()
    assert m.n_components == 1
    assert m.face_size_histogram == {4: 2 * 20**level + 4 * 8**level}
    assert m.n_edges == 2 * m.n_faces
    assert m.volume == pytest.approx(8.0 * (20 / 27) ** level, rel=1e-10)
    assert_agrees_with_peers(m, expect_genus=sponge_genus(level))


def test_menger_sponge_level4():
    m = topomesh.menger_sponge(4)
    m.validate()
    assert m.genus == sponge_genus(4) == 26433
    assert m.volume == pytest.approx(8.0 * (20 / 27) ** 4, rel=1e-10)
    assert_agrees_with_peers(m)


def test_menger_sponge_vertices_on_grid_and_inside_cube():
    m = topomesh.menger_sponge(2)
    v = (m.vertices + 1.0) * 9 / 2
    np.testing.assert_allclose(v, np.round(v), atol=1e-12)
    assert v.min() == 0 and v.max() == 9
    assert len(np.unique(np.round(v), axis=0)) == m.n_vertices


def test_menger_sponge_rejects_bad_levels():
    with pytest.raises(topomesh.MeshError):
        topomesh.menger_sponge(6)
    # issue 14: a MeshError naming the parameter, no bare OverflowError
    with pytest.raises(topomesh.MeshError, match=r"menger_sponge: level = -1 must be in \[0, 5\]"):
        topomesh.menger_sponge(-1)


# --- generalized Menger sponge (dissertation ch. VII)


def test_menger_cube_first_iterations_are_classic():
    c = topomesh.cube()
    m1 = c.menger()
    m1.validate()
    assert (m1.n_vertices, m1.n_edges, m1.n_faces, m1.genus) == (64, 144, 72, 5)
    assert m1.volume == pytest.approx(8 * 20 / 27, rel=1e-12)
    # same vertex set as the classic level-1 sponge
    s1 = topomesh.menger_sponge(1)
    assert sorted(map(tuple, np.round(m1.vertices, 9))) == sorted(map(tuple, np.round(s1.vertices, 9)))
    m2 = c.menger(2)
    assert m2.genus == sponge_genus(2) == 81
    assert m2.volume == pytest.approx(8 * (20 / 27) ** 2, rel=1e-9)


# (input, iterations, construction): the default per-face corners, and the
# dissertation's merged ones (offset="merged", VII.4) where they still cross
MENGER_CASES = [("cube", 4, "per_face"), ("tetrahedron", 4, "per_face"), ("dodecahedron", 3, "per_face"),
                ("dodecahedron", 3, "merged")]
# iterations that still self-intersect (src/schemes/menger/mod.rs, Status):
# Mesh.menger warns on them; none with the default construction
MENGER_CROSSING = {("merged", "tetrahedron", 4), ("merged", "dodecahedron", 3), ("merged", "dodecahedron", 4)}
# iterations whose depth went below the requested thickness (mod.rs, "Per-face
# corners", invariants 3 and 6: the bound at sharp edges and the local
# reduction): Mesh.menger warns with the faces reduced (the merged
# construction's reduced case, the torus's second iteration, is in
# tests/test_menger_offset.py)
MENGER_REDUCED = {("per_face", "tetrahedron", k) for k in (1, 2, 3, 4)} | {("per_face", "dodecahedron", k) for k in (2, 3)}


def menger_step(m, name, k, offset="per_face"):
    """One Menger iteration of the k-th level, expecting GeometryWarning
    exactly where the iteration is known to self-intersect or to have its
    thickness reduced (pytest turns any other warning into an error)."""
    if (offset, name, k) in MENGER_REDUCED:
        with pytest.warns(topomesh.GeometryWarning, match=r"iteration 1 of 1: the thickness was reduced on \d+ of \d+ faces"):
            return m.menger(offset=offset)
    if (offset, name, k) not in MENGER_CROSSING:
        return m.menger(offset=offset)
    with pytest.warns(topomesh.GeometryWarning, match=r"iteration 1 of 1 self-intersects: \d+ crossing triangle pairs remain"):
        return m.menger(offset=offset)


@pytest.mark.parametrize("name,iterations,offset", MENGER_CASES)
def test_menger_genus_recurrence_and_peers(name, iterations, offset):
    m = PLATONIC[name]()
    for k in range(1, iterations + 1):
        g, f = m.genus, m.n_faces
        m = menger_step(m, name, k, offset)
        m.validate()
        assert m.genus == 2 * g + f - 1, f"{name} iteration {k}"
        assert m.n_components == 1
        assert min(m.face_size_histogram) >= 3  # no one-gons or two-gons
        assert m.volume > 0
        assert_agrees_with_peers(m)


def test_menger_dodecahedron_fourth_iteration_topology():
    """The merged construction (the per-face one, the default, has no
    crossing here: tests/test_menger_offset.py; its fourth iteration is
    measured in docs/schemes/menger.md)."""
    # one warning per crossing iteration, naming it: only the third crosses
    with pytest.warns(topomesh.GeometryWarning) as rec:
        m = topomesh.dodecahedron().menger(3, offset="merged")
    assert [str(w.message).split(":")[1].strip() for w in rec] == ["iteration 3 of 3 self-intersects"]
    g, f = m.genus, m.n_faces
    # without the thickness reduction: its whole-output scan and rebuilds take
    # minutes at 660 k faces (76,817 pairs left with it, docs/schemes/menger.md)
    with pytest.warns(topomesh.GeometryWarning, match=r"iteration 1 of 1 self-intersects: .* left \d+ input vertices"):
        m = m.menger(reduce_thickness=False, offset="merged")
    m.validate()
    assert m.genus == 2 * g + f - 1
    assert m.n_components == 1 and m.volume > 0
    assert min(m.face_size_histogram) >= 3
    # 1.68 M faces: trimesh and manifold3d agree too (no coincident points)
    assert_agrees_with_peers(m)


def test_menger_cube_counts():
    # all quads; genus 5, 81, 1121, 15585
    m = topomesh.cube()
    got = []
    for _ in range(4):
        m = m.menger()
        got.append((m.n_faces, m.genus))
        assert set(m.face_size_histogram) == {4}
    assert [g for _, g in got] == [5, 81, 1121, 15585]


def test_menger_options_and_errors():
    c = topomesh.cube()
    a = c.menger(thickness=0.25, absolute=True)
    a.validate()
    assert a.genus == 5 and a.volume > 0
    assert_agrees_with_peers(a)
    with pytest.raises(topomesh.MeshError):
        c.menger(thickness=0.5)
    with pytest.raises(topomesh.MeshError):
        c.sierpinski().menger()  # self-loops have no length
    assert c.menger(0) == c


@pytest.mark.parametrize("name", ["tetrahedron", "dodecahedron"])
def test_menger_faces_planar_and_pipes_unsplit(name):
    """Remeshing corners follow merged offset corners (src/schemes/menger/mod.rs,
    step 2; offset="merged"), so pipe walls stay planar quads instead of being
    split into two long triangles: every face of the second iteration is planar."""
    m = PLATONIC[name]().menger(2, offset="merged")
    v, sizes, idx = m.vertices, m.face_sizes, m.face_indices
    start = np.concatenate([[0], np.cumsum(sizes)])
    worst = 0.0
    for f in range(m.n_faces):
        p = v[idx[start[f]:start[f + 1]]]
        n = np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)
        n /= np.linalg.norm(n)
        size = np.linalg.norm(p - np.roll(p, 1, axis=0), axis=1).max()
        worst = max(worst, float(np.abs((p - p.mean(axis=0)) @ n).max() / size))
    assert worst < 1e-9
    if name == "tetrahedron":
        # 60 triangles beside 462 quads; with pipe walls split (inset
        # remeshing corners under merged offset corners) it was 324 and 342
        hist = m.face_size_histogram
        assert hist[3] * 5 < hist[4]


def test_menger_warns_only_where_crossings_remain():
    from tests.test_ops import self_intersections

    # crossing-free: no warning (pytest's filterwarnings turns one into an error);
    # made crossing-free by the thickness reduction, a warning saying where:
    # tests/test_menger_offset.py (the torus's second iteration)
    # (the merged construction: the default has no crossing here)
    topomesh.tetrahedron().menger(3, offset="merged")
    d2 = topomesh.dodecahedron().menger(2, offset="merged")
    with pytest.warns(topomesh.GeometryWarning) as rec:
        d3 = d2.menger(offset="merged")
    assert len(rec) == 1
    n = int(str(rec[0].message).split("self-intersects: ")[1].split()[0])
    assert n == len(d3.self_intersections()) > 0
    # the warning is about a real defect: an independent exact scan finds crossings
    # (libigl's CGAL test, 0.8 s; the NumPy checker of test_ops takes minutes here)
    try:
        import igl.copyleft.cgal as cgal
    except ImportError:
        assert self_intersections(d3)
    else:
        v, t, _ = d3.triangulate()
        assert len(cgal.remesh_self_intersections(v, t, detect_only=True)[2]) > 0
    # the result is still the valid manifold it would be without the warning
    d3.validate()
    assert d3.genus == 2 * d2.genus + d2.n_faces - 1
    # (the message of a multi-iteration call: the fourth-iteration test)


# Crossing-free cases (the Rust scan in src/schemes/menger/mod.rs covers the
# larger ones, cube 1–4). An independent numpy checker from test_ops: the
# tetrahedron's second iteration had 24 crossing triangle pairs before the
# material-depth rule of the module docs, its third 1304 before the crossing
# check (fully collapsed vertices).
CROSSING_FREE = [("cube", 2), ("tetrahedron", 1), ("tetrahedron", 2), ("tetrahedron", 3), ("dodecahedron", 1)]


@pytest.mark.parametrize("name,iterations", CROSSING_FREE)
def test_menger_no_self_intersections(name, iterations):
    from tests.test_ops import self_intersections

    with warnings.catch_warnings():
        # the tetrahedron's third iteration warns that its thickness was
        # reduced (to remove 4 coplanar contacts); the scan below checks it
        warnings.simplefilter("ignore", topomesh.GeometryWarning)
        m = PLATONIC[name]().menger(iterations)
    m.validate()
    bad = self_intersections(m)
    assert not bad, f"{len(bad)} crossing triangle pairs, e.g. {bad[:3]}"


@pytest.mark.parametrize("thickness", [0.25, 0.3])
def test_menger_tetrahedron_second_iteration_crossing_free_other_thickness(thickness):
    from tests.test_ops import self_intersections

    # the tetrahedron's 70.5° edges bound the depth (a GeometryWarning says so)
    with pytest.warns(topomesh.GeometryWarning, match="thickness was reduced"):
        m1 = topomesh.tetrahedron().menger(1, thickness=thickness)
    with pytest.warns(topomesh.GeometryWarning, match="thickness was reduced"):
        m = m1.menger(thickness=thickness)
    m.validate()
    assert m1.genus == 2 * 0 + 4 - 1 and m.genus == 2 * m1.genus + m1.n_faces - 1
    assert not self_intersections(m)
    assert_agrees_with_peers(m)
