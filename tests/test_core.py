"""Core mesh: primitives against the peers, construction errors, exports,
the fundamental operators, files and conversions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import topomesh
from topomesh import Mesh, MeshError
from tests.harness import assert_agrees_with_peers

PRIMITIVES = {
    "tetrahedron": (topomesh.tetrahedron, (4, 6, 4)),
    "cube": (topomesh.cube, (8, 12, 6)),
    "octahedron": (topomesh.octahedron, (6, 12, 8)),
    "dodecahedron": (topomesh.dodecahedron, (20, 30, 12)),
    "icosahedron": (topomesh.icosahedron, (12, 30, 20)),
}


@pytest.mark.parametrize("name", PRIMITIVES)
def test_platonic_solids_agree_with_peers(name):
    make, (v, e, f) = PRIMITIVES[name]
    m = make()
    assert (m.n_vertices, m.n_edges, m.n_faces) == (v, e, f)
    assert_agrees_with_peers(m, expect_genus=0)
    # centred, and every vertex on one sphere (regular solids)
    r = np.linalg.norm(m.vertices, axis=1)
    assert np.allclose(m.vertices.mean(axis=0), 0, atol=1e-12)
    assert np.ptp(r) < 1e-12


@pytest.mark.parametrize("major,minor", [(3, 3), (8, 5), (24, 12)])
def test_torus_agrees_with_peers(major, minor):
    m = topomesh.torus(major, minor, 1.0, 0.3)
    assert (m.n_vertices, m.n_edges, m.n_faces) == (major * minor, 2 * major * minor, major * minor)
    assert_agrees_with_peers(m, expect_genus=1)


@pytest.mark.parametrize("g", [1, 2, 3, 4, 5])
def test_genus_surface_agrees_with_peers(g):
    m = topomesh.genus_surface(g)
    assert_agrees_with_peers(m, expect_genus=g)
    assert m.face_size_histogram == {4: m.n_faces}


def test_disjoint_components_count_in_the_harness():
    # a cube and a torus side by side: genus 1 in total, two components
    c, t = topomesh.cube(), topomesh.torus(8, 6, 1.0, 0.3)
    verts = np.vstack([c.vertices, t.vertices + [5.0, 0, 0]])
    idx = np.concatenate([c.face_indices, t.face_indices + c.n_vertices])
    m = Mesh.from_flat(verts, np.concatenate([c.face_sizes, t.face_sizes]), idx)
    assert (m.n_components, m.genus, m.component_genera) == (2, 1, [0, 1])
    assert_agrees_with_peers(m)


# ------------------------------------------------------------------ bad input

TET_V = np.array([[1.0, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]])
TET_F = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]


def test_valid_tetrahedron_builds():
    assert Mesh.from_polygons(TET_V, TET_F).genus == 0


@pytest.mark.parametrize(
    "verts,faces,match",
    [
        (TET_V, [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 7]], r"face 3: vertex index 7 at position 2 is out of range"),
        (TET_V, [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, -1]], r"face 3: vertex index -1"),
        (TET_V, [[0, 1, 2], [0, 3, 1], [], [1, 3, 2]], r"face 2 is empty"),
        (TET_V, [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 2, 3]], r"faces \d and \d are inconsistently oriented"),
        (np.vstack([TET_V, [[0, 0, 5]]]), [[0, 1, 2], [1, 0, 3], [0, 1, 4]], r"edge \(0, 1\) is used by 3 face sides"),
        (TET_V[:3], [[0, 1, 2]], r"edge \(\d, \d\) of face 0 is a boundary edge"),
        (np.array([[1.0, 1, 1], [1, -1, -1], [-1, np.nan, -1], [-1, -1, 1]]), TET_F, r"vertex 2 has a NaN or infinite"),
        (np.array([[1.0, 1, 1], [1, -1, -1], [-1, np.inf, -1], [-1, -1, 1]]), TET_F, r"vertex 2 has a NaN or infinite"),
        (TET_V[:, :2], TET_F, r"vertices: shape \[4, 2\] is not \(V, 3\)"),
        (TET_V.astype(complex), TET_F, r"vertices: dtype complex128 is not a real number type"),
        (TET_V, np.array(TET_F, dtype=float), r"faces: dtype float64 is not an integer type"),
        (TET_V, [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1.5, 3, 2]], r"face 3: dtype float64 is not an integer type"),
        (np.vstack([TET_V, [[9, 9, 9]]]), TET_F, r"vertex 4 is not used by any face"),
    ],
)
def test_bad_input_raises_mesh_error(verts, faces, match):
    with pytest.raises(MeshError, match=match):
        # open meshes are accepted by default: the boundary case asks for the strict check
        Mesh.from_polygons(verts, faces, boundaries="refuse")


def test_non_manifold_vertex_is_named():
    # two tetrahedra sharing vertex 0 (a pinch)
    v = np.vstack([TET_V, TET_V[1:] + [3.0, 0, 0]])
    f = TET_F + [[0 if i == 0 else i + 3 for i in face] for face in TET_F]
    with pytest.raises(MeshError, match=r"vertex 0 is non-manifold"):
        Mesh.from_polygons(v, f)


def test_mesh_error_is_a_value_error_and_input_is_untouched():
    assert issubclass(MeshError, ValueError)
    v = TET_V.copy()
    f = np.array(TET_F)
    m = Mesh.from_polygons(v, f)
    assert np.array_equal(v, TET_V) and np.array_equal(f, TET_F)
    out = m.vertices
    with pytest.raises(ValueError, match="read-only"):
        out[:] = 0  # a read-only view: the mesh keeps its coordinates
    mine = np.array(out)
    mine[:] = 0  # a copy is the user's own
    assert np.array_equal(m.vertices, TET_V)


def test_flat_layout_checks_sizes():
    with pytest.raises(MeshError, match=r"face sizes add up to 6 but 5 face indices"):
        Mesh.from_flat(TET_V, [3, 3], [0, 1, 2, 0, 3])
    with pytest.raises(MeshError, match=r"face 1 has negative size"):
        Mesh.from_flat(TET_V, [3, -3], [0, 1, 2])


def test_close_boundaries_caps_holes_and_hides_them():
    # an open box (cube without its top): one boundary loop
    c = topomesh.cube()
    keep = [0, 1, 2, 3, 4]  # faces other than the last
    sizes, idx = c.face_sizes, c.face_indices
    off = np.concatenate([[0], np.cumsum(sizes)])
    faces = [idx[off[i] : off[i + 1]] for i in keep]
    dropped = [i for i in range(6) if i not in keep][0]
    with pytest.raises(MeshError, match="boundary edge"):
        Mesh.from_polygons(c.vertices, faces, close_boundaries=False)
    m = Mesh.from_polygons(c.vertices, faces, close_boundaries=True)
    m.validate()
    # χ of the open box (a disk) is 1; capping its hole gives the sphere's 2
    assert (m.n_faces, m.n_holes, m.genus, m.euler_characteristic) == (6, 1, 0, 1)
    assert m == Mesh.from_polygons(c.vertices, faces)  # keeping boundaries is the default
    assert len(m.face_sizes) == 5 and dropped == 5
    assert m.triangles().shape == (10, 3)


# -------------------------------------------------------------------- exports


def test_exports_round_trip():
    m = topomesh.genus_surface(2)
    again = Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices)
    assert again == m
    padded = m.padded_faces
    assert padded[0] == m.face_sizes[0] and len(padded) == m.n_faces + len(m.face_indices)
    assert m.edges.shape == (m.n_edges, 2)
    assert m.face_centroids.shape == m.face_normals.shape == (m.n_faces, 3)
    assert np.allclose(np.linalg.norm(m.vertex_normals, axis=1), 1)


def test_star_face_is_ear_clipped():
    # a flat 5-pointed star prism: its two star faces are non-convex decagons
    k = np.arange(10)
    r = np.where(k % 2 == 0, 1.0, 0.38)
    a = 2 * np.pi * k / 10
    ring = np.column_stack([r * np.cos(a), r * np.sin(a)])
    verts = np.vstack([np.column_stack([ring, np.zeros(10)]), np.column_stack([ring, np.ones(10)])])
    faces = [list(range(9, -1, -1)), list(range(10, 20))] + [[i, (i + 1) % 10, (i + 1) % 10 + 10, i + 10] for i in range(10)]
    m = Mesh.from_polygons(verts, faces)
    tris, src = m.triangles(return_faces=True)
    top = tris[src == 1]
    assert len(top) == 8
    p = verts[top]
    cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    assert np.all(cross[:, 2] > 0), "a clipped triangle is inverted: it leaves the star"
    x, y = ring[:, 0], ring[:, 1]
    star_area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    assert math.isclose(cross[:, 2].sum() / 2, star_area, rel_tol=1e-12)
    assert_agrees_with_peers(m, expect_genus=0)


def test_dropped_self_loops_keep_triangles_closed():
    m, e = topomesh.cube().insert_edge(2, 1, 2, 1)  # a self-loop at a corner: a one-gon
    assert (m.n_self_loops, m.face_size_histogram) == (1, {1: 1, 4: 5, 5: 1})
    tris = m.triangles()
    assert len(tris) == 12
    r = topomesh.Mesh.from_polygons(m.vertices, tris)
    assert r.genus == 0 and r.n_edges == 18


# ------------------------------------------------------------------ operators


def test_operators_return_new_meshes():
    c = topomesh.cube()
    m, e = c.insert_edge(0, 0, 0, 2)
    assert (c.n_edges, m.n_edges, e) == (12, 13, 12)
    assert m.face_size_histogram == {3: 2, 4: 5}
    back = m.delete_edge(e)
    assert back.n_edges == 12 and back.face_size_histogram == {4: 6}
    h, _ = c.insert_edge(0, 0, 1, 0)  # opposite faces: a handle
    assert (h.genus, h.n_faces) == (1, 5)
    p, v, f = c.create_vertex([0, 0, 5])
    assert (p.n_components, p.n_vertices, v, f) == (2, 9, 8, 6)
    joined, _ = p.insert_edge(f, 0, 0, 0)
    assert (joined.n_components, joined.genus) == (1, 0)
    with pytest.raises(MeshError, match="not a point-sphere"):
        c.delete_vertex(0)
    assert p.delete_vertex(v) == c
    with pytest.raises(MeshError, match=r"face 6 out of range"):
        c.insert_edge(6, 0, 0, 0)
    with pytest.raises(MeshError, match=r"position 4 is out of range"):
        c.insert_edge(0, 4, 0, 0)
    with pytest.raises(MeshError, match=r"edge 12 out of range"):
        c.delete_edge(12)
    with pytest.raises(MeshError, match="NaN or infinite"):
        c.create_vertex([0, np.nan, 0])


def _corner_count(m):
    return m.face_sizes.tolist()


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_random_operator_sequences_keep_contracts(data):
    m = data.draw(
        st.one_of(
            st.sampled_from([topomesh.tetrahedron(), topomesh.cube(), topomesh.octahedron(), topomesh.dodecahedron()]),
            st.builds(topomesh.torus, st.integers(3, 7), st.integers(3, 6), st.just(2.0), st.just(0.5)),
            st.builds(topomesh.genus_surface, st.integers(0, 3)),
        )
    )
    for _ in range(data.draw(st.integers(1, 25))):
        sizes = m.face_sizes
        chi, comps, genus, f = m.euler_characteristic, m.n_components, m.genus, m.n_faces
        op = data.draw(st.sampled_from(["insert", "insert", "delete", "create"]))
        if op == "create" or m.n_edges == 0:
            m, _, _ = m.create_vertex([0.0, 0.0, 0.0])
            assert (m.n_components, m.genus, m.euler_characteristic) == (comps + 1, genus, chi + 2)
        elif op == "insert":
            f1 = data.draw(st.integers(0, len(sizes) - 1))
            f2 = data.draw(st.integers(0, len(sizes) - 1))
            p1 = data.draw(st.integers(0, int(sizes[f1]) - 1))
            p2 = data.draw(st.integers(0, int(sizes[f2]) - 1))
            m, _ = m.insert_edge(f1, p1, f2, p2)
            if f1 == f2:
                assert (m.n_faces, m.euler_characteristic, m.genus) == (f + 1, chi, genus)
            else:
                assert m.n_faces == f - 1 and m.euler_characteristic == chi - 2
                assert (m.genus, m.n_components) in {(genus + 1, comps), (genus, comps - 1)}
        else:
            e = data.draw(st.integers(0, m.n_edges - 1))
            m = m.delete_edge(e)
            assert m.euler_characteristic in (chi, chi + 2)
            if m.euler_characteristic == chi + 2:
                assert (m.genus, m.n_components) in {(genus - 1, comps), (genus, comps + 1)}
            else:
                assert (m.genus, m.n_components, m.n_faces) == (genus, comps, f - 1)
        m.validate()


# ---------------------------------------------------------------- files, interop


@pytest.mark.parametrize("ext", ["obj", "off", "ply"])
def test_files_round_trip_exactly(tmp_path, ext):
    rng = np.random.default_rng(1)
    base = topomesh.genus_surface(2)
    m = base.with_vertices(base.vertices + rng.normal(scale=1e-3, size=base.vertices.shape))
    m, _ = m.insert_edge(3, 1, 3, 1)  # a self-loop survives the trip
    p = tmp_path / f"m.{ext}"
    m.save(p)
    r = topomesh.load(p)
    assert r == m
    assert np.array_equal(r.vertices, m.vertices)
    assert r.n_self_loops == 1


def test_load_errors_are_mesh_errors(tmp_path):
    with pytest.raises(MeshError, match="unsupported extension '.vtk'"):
        topomesh.load(tmp_path / "x.vtk")
    with pytest.raises(MeshError, match="no such file"):
        topomesh.load(tmp_path / "missing.obj")
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 9\n")
    with pytest.raises(MeshError, match=r"face 0: vertex index 9"):
        topomesh.load(bad)
    junk = tmp_path / "junk.ply"
    junk.write_text("not a ply file")
    with pytest.raises(MeshError, match="cannot read PLY"):
        topomesh.load(junk)


def test_conversions():
    m = topomesh.torus(10, 6)
    tm = m.to_trimesh()
    assert tm.is_watertight and len(tm.faces) == 2 * m.n_faces
    pv = m.to_pyvista()
    assert pv.n_cells == m.n_faces and pv.n_points == m.n_vertices
    from topomesh._interop import from_pyvista, from_trimesh

    assert from_pyvista(pv) == m
    assert from_trimesh(tm).genus == 1
    man = m.to_manifold()
    assert man.genus() == 1


@pytest.mark.parametrize(
    "scheme",
    ["catmull_clark", "doo_sabin", "loop", "sqrt3", "simplest", "midpoint", "dual", "honeycomb", "vertex_truncation", "sierpinski", "menger"],
)
def test_every_scheme_rejects_negative_iterations_and_shows_progress(scheme, capsys):
    cube = topomesh.cube()
    with pytest.raises(MeshError, match=rf"{scheme}: iterations = -1 must be >= 0"):
        getattr(cube, scheme)(iterations=-1)
    assert getattr(cube, scheme)(iterations=0) == cube
    getattr(cube, scheme)(iterations=1, progress=True)
    assert "1/1" in capsys.readouterr().err  # the tqdm bar


@pytest.mark.parametrize("scheme", ["catmull_clark", "loop", "dual"])
def test_multi_level_call_releasing_the_heap_equals_its_steps(scheme):
    # the level before the last has >= 2**17 half-edges, so the call returns
    # glibc's free heap pages before it (src/python/alloc.rs); nothing else changes
    m = topomesh.torus(400, 100) if scheme == "dual" else topomesh.torus(120, 80)
    step = getattr(m, scheme)(iterations=1)
    assert 2 * step.n_edges >= 1 << 17
    two = getattr(m, scheme)(iterations=2)
    assert two == getattr(step, scheme)(iterations=1)
    np.testing.assert_array_equal(two.vertices, getattr(step, scheme)(iterations=1).vertices)
