"""The repair path (topomesh.repair), STL reading, Mesh.from_trimesh /
Mesh.from_pyvista, and the inside-out warning of the constructors
(issue 14, reproducer 6)."""

from __future__ import annotations

import subprocess
import sys
import warnings

import numpy as np
import pytest
import pyvista as pv
import trimesh

import topomesh
from topomesh import GeometryWarning, Mesh, MeshError, RepairReport
from topomesh.stl import read_stl

from tests.harness import assert_agrees_with_peers


@pytest.fixture(scope="module")
def sphere() -> trimesh.Trimesh:
    return trimesh.creation.icosphere(subdivisions=3)


def soup_of(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every triangle with its own three vertices, as STL stores them."""
    return v[f].reshape(-1, 3), np.arange(3 * len(f)).reshape(-1, 3)


def same_surface(m: Mesh, tm: trimesh.Trimesh) -> None:
    assert (m.n_vertices, m.n_faces, m.n_holes) == (len(tm.vertices), len(tm.faces), 0)
    assert m.genus == (2 - tm.euler_number) // 2
    assert m.volume == pytest.approx(tm.volume, rel=1e-12)


def test_a_soup_welds_back_into_the_sphere(sphere):
    v, f = soup_of(sphere.vertices, sphere.faces)
    m, r = topomesh.repair(v, f)
    same_surface(m, sphere)
    assert r.vertices_merged == 3 * len(sphere.faces) - len(sphere.vertices)
    assert (r.faces_flipped, r.components_flipped, r.boundary_loops) == (0, 0, 0)
    assert r.changed
    assert_agrees_with_peers(m, expect_genus=0)
    # the trimesh soup itself, through Mesh.from_trimesh
    tsoup = trimesh.Trimesh(v, f, process=False)
    with pytest.raises(MeshError, match="boundary"):
        Mesh.from_trimesh(tsoup, boundaries="refuse")
    # by default the soup is kept as it is: one open triangle per face
    loose = Mesh.from_trimesh(tsoup)
    assert (loose.n_components, loose.n_boundary_loops) == (len(f), len(f))
    same_surface(Mesh.from_trimesh(tsoup, repair=True), sphere)


def test_randomly_flipped_faces_are_oriented(sphere):
    rng = np.random.default_rng(7)
    flip = rng.random(len(sphere.faces)) < 0.3
    f = np.where(flip[:, None], sphere.faces[:, ::-1], sphere.faces)
    v, f = soup_of(sphere.vertices, f)
    m, r = topomesh.repair(v, f)
    same_surface(m, sphere)
    assert r.faces_flipped == flip.sum()
    assert r.components_flipped == 0
    assert_agrees_with_peers(m, expect_genus=0)


def test_duplicated_and_degenerate_faces_are_dropped(sphere):
    rng = np.random.default_rng(3)
    extra = sphere.faces[rng.choice(len(sphere.faces), 10, replace=False)]
    extra[::2] = extra[::2, ::-1]  # some repeated the other way round
    extra[1::3] = np.roll(extra[1::3], 1, axis=1)  # some rotated
    degenerate = [[0, 0, 1]]
    f = np.concatenate([sphere.faces, extra, degenerate])
    m, r = topomesh.repair(sphere.vertices, f)
    same_surface(m, sphere)
    assert (r.duplicate_faces_dropped, r.degenerate_faces_dropped) == (10, 1)
    assert r.vertices_merged == 0
    # a zero-area face with three distinct vertices: a collinear midpoint
    v = np.concatenate([sphere.vertices, [(sphere.vertices[0] + sphere.vertices[1]) / 2]])
    m, r = topomesh.repair(v, np.concatenate([sphere.faces, [[0, len(v) - 1, 1]]]), tolerance=0)
    assert (r.degenerate_faces_dropped, r.unreferenced_vertices_removed) == (1, 1)
    same_surface(m, sphere)


def test_a_jittered_soup_needs_a_tolerance(sphere):
    v, f = soup_of(sphere.vertices, sphere.faces)
    rng = np.random.default_rng(11)
    v = v + rng.uniform(-1e-12, 1e-12, v.shape)
    with pytest.raises(MeshError, match="boundary"):
        topomesh.repair(v, f, tolerance=0, close_boundaries=False)
    pieces, r0 = topomesh.repair(v, f, tolerance=0)
    assert pieces.n_components == len(sphere.faces) and r0.boundary_loops == len(sphere.faces)
    m, r = topomesh.repair(v, f, tolerance=1e-9)
    assert r.tolerance == 1e-9
    assert (m.n_vertices, m.n_faces, m.genus) == (len(sphere.vertices), len(sphere.faces), 0)
    assert_agrees_with_peers(m, expect_genus=0, planar=False)


def test_cubes_sharing_a_vertex_are_split_apart():
    a = trimesh.creation.box()
    b = trimesh.creation.box()
    b.apply_translation([1.0, 1.0, 1.0])
    v = np.concatenate([a.vertices, b.vertices])
    f = np.concatenate([a.faces, b.faces + len(a.vertices)])
    welded, inverse = np.unique(v, axis=0, return_inverse=True)
    with pytest.raises(MeshError, match="non-manifold"):
        Mesh.from_polygons(welded, inverse.ravel()[f])  # the shared corner is a pinch
    m, r = topomesh.repair(welded, inverse.ravel()[f])
    assert (r.vertices_merged, r.pinched_vertices_split) == (0, 1)
    assert (m.n_vertices, m.n_components, m.component_genera) == (16, 2, [0, 0])
    m, r = topomesh.repair(v, f)
    assert (r.vertices_merged, r.pinched_vertices_split) == (1, 1)
    assert (m.n_vertices, m.n_components, m.component_genera) == (16, 2, [0, 0])
    assert m.volume == pytest.approx(2.0)


def test_an_inside_out_sphere_warns_and_is_oriented_outward(sphere):
    inverted = sphere.faces[:, ::-1]
    with pytest.warns(GeometryWarning, match=r"component 0 \(volume -4\.1.*topomesh\.repair"):
        bad = Mesh.from_polygons(sphere.vertices, inverted)
    assert bad.volume < 0
    with pytest.warns(GeometryWarning, match="inside out"):
        Mesh.from_flat(sphere.vertices, np.full(len(inverted), 3), inverted.ravel())
    m, r = topomesh.repair(sphere.vertices, inverted)
    assert (r.components_flipped, r.faces_flipped) == (1, 0)
    assert m.volume == pytest.approx(sphere.volume)
    assert_agrees_with_peers(m, expect_genus=0)


def test_no_warning_for_outward_flat_or_open_components(sphere):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Mesh.from_polygons(sphere.vertices, sphere.faces)
        # a flat closed component: a square seen from both sides
        Mesh.from_polygons([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3], [3, 2, 1, 0]])
        # an open, inverted hemisphere capped by a hole: not closed, no volume to judge
        keep = sphere.triangles_center[:, 2] > 0
        used = np.unique(sphere.faces[keep])
        new = np.full(len(sphere.vertices), -1)
        new[used] = np.arange(len(used))
        Mesh.from_polygons(sphere.vertices[used], new[sphere.faces[keep]][:, ::-1], close_boundaries=True)


def test_report_prints_the_counts_that_changed():
    cube = topomesh.cube()
    m, r = topomesh.repair(cube.vertices, cube.face_indices.reshape(-1, 4))
    assert m == cube
    assert not r.changed and "nothing to change" in str(r)
    m, r = topomesh.repair(cube.vertices, cube.face_indices.reshape(-1, 4)[:, ::-1])
    assert r.changed and str(r).splitlines()[1:] == ["  1 closed components flipped outward"]
    assert isinstance(r, RepairReport)
    with pytest.raises(Exception):
        r.faces_flipped = 3  # frozen


def test_repair_rejects_bad_input_naming_it():
    v = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    before = v.copy()
    with pytest.raises(MeshError, match="face 0: vertex index 3 at position 2"):
        topomesh.repair(v, [[0, 1, 3]])
    with pytest.raises(MeshError, match="tolerance = -1"):
        topomesh.repair(v, [[0, 1, 2]], tolerance=-1.0)
    with pytest.raises(MeshError, match="tolerance"):
        topomesh.repair(v, [[0, 1, 2]], tolerance=float("inf"))
    with pytest.raises(MeshError, match="tolerance = 'x' is not a number"):
        topomesh.repair(v, [[0, 1, 2]], tolerance="x")
    with pytest.raises(MeshError, match="face 1 is empty"):
        topomesh.repair(v, [[0, 1, 2], []])
    with pytest.raises(MeshError, match="vertex 1 has a NaN"):
        topomesh.repair([[0.0, 0, 0], [np.nan, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    with pytest.raises(MeshError, match=r"edge \(\d, \d\) of face 0 is a boundary"):
        topomesh.repair(v, [[0, 1, 2]], boundaries="refuse")
    with pytest.raises(MeshError, match=r'repair: boundaries = "open" is not an option; allowed: "keep"'):
        topomesh.repair(v, [[0, 1, 2]], boundaries="open")
    m, r = topomesh.repair(v, [[0, 1, 2]])
    assert (m.n_holes, r.boundary_loops) == (1, 1)
    assert m == topomesh.repair(v, [[0, 1, 2]], close_boundaries=True)[0]
    np.testing.assert_array_equal(v, before)


def test_from_pyvista_polygons_strips_and_grids():
    s = pv.Sphere()
    m = Mesh.from_pyvista(s)
    assert (m.n_vertices, m.n_faces) == (s.n_points, s.n_cells)
    assert_agrees_with_peers(m, expect_genus=0)
    strips = s.strip()
    assert strips.n_strips > 0 and strips.GetPolys().GetNumberOfCells() == 0
    ms = Mesh.from_pyvista(strips)
    assert (ms.n_vertices, ms.n_faces, ms.genus) == (s.n_points, s.n_cells, 0)
    assert ms.volume == pytest.approx(m.volume, rel=1e-12)
    assert_agrees_with_peers(ms, expect_genus=0)
    grid = pv.ImageData(dimensions=(3, 3, 3)).cast_to_unstructured_grid()
    mg = Mesh.from_pyvista(grid)
    assert (mg.n_vertices, mg.n_faces, mg.face_size_histogram) == (26, 24, {4: 24})
    assert mg.volume == pytest.approx(8.0)
    assert_agrees_with_peers(mg, expect_genus=0)
    # repair on request, and points no face uses are left out
    extra = pv.PolyData(np.concatenate([s.points, [[5.0, 5.0, 5.0]]]), s.faces)
    assert Mesh.from_pyvista(extra) == m
    assert Mesh.from_pyvista(s, repair=True).n_faces == s.n_cells
    with pytest.raises(MeshError, match="expected a pyvista dataset"):
        Mesh.from_pyvista([1, 2, 3])


def test_strip_triangles_alternate_orientation():
    # one strip of 6 points over a flat band: 4 triangles, all facing +z
    pts = np.array([[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0], [2, 0, 0], [2, 1, 0]], dtype=float)
    band = pv.PolyData(pts, strips=np.array([6, 0, 1, 2, 3, 4, 5]))
    m = Mesh.from_pyvista(band, close_boundaries=True)
    assert m.n_faces - m.n_holes == 4
    normals = m.face_normals[: m.n_faces - m.n_holes]
    assert np.allclose(normals, normals[0]) and abs(normals[0][2]) == pytest.approx(1.0)


def test_from_trimesh_torus():
    tm = trimesh.creation.torus(major_radius=1.0, minor_radius=0.3)
    m = Mesh.from_trimesh(tm)
    same_surface(m, tm)
    assert m.genus == 1
    assert_agrees_with_peers(m, expect_genus=1)
    # the module function keeps working with its old arguments
    assert topomesh._interop.from_trimesh(tm) == m


@pytest.mark.parametrize("make", [lambda: trimesh.creation.torus(1.0, 0.3), trimesh.creation.box, lambda: trimesh.creation.icosphere(2)])
@pytest.mark.parametrize("file_type", ["stl", "stl_ascii"])
def test_stl_from_trimesh_reads_back_closed(tmp_path, make, file_type):
    tm = make()
    path = tmp_path / "m.stl"
    data = tm.export(file_type=file_type)
    path.write_bytes(data if isinstance(data, bytes) else data.encode())
    v, t = read_stl(path)
    assert v.dtype == np.float64 and t.dtype == np.int64 and t.shape == (len(tm.faces), 3)
    m = Mesh.from_polygons(v, t)  # TEMPORARY: topomesh.load() will dispatch .stl here
    assert (m.n_vertices, m.n_faces, m.n_holes) == (len(tm.vertices), len(tm.faces), 0)
    assert m.genus == (2 - tm.euler_number) // 2
    assert m.volume == pytest.approx(tm.volume, rel=1e-5)  # STL stores float32
    assert_agrees_with_peers(m)


def test_malformed_stl_names_path_and_line(tmp_path):
    p = tmp_path / "bad.stl"
    p.write_bytes(b"\0" * 90)
    with pytest.raises(MeshError, match=r"bad\.stl: not an STL file"):
        read_stl(p)
    p.write_text("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n")
    with pytest.raises(MeshError, match=r"bad\.stl: line 5: malformed vertex line 'vertex 1 0'"):
        read_stl(p)
    p.write_text("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zero\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n")
    with pytest.raises(MeshError, match=r"line 5: vertex coordinates 'vertex 1 0 zero' are not numbers"):
        read_stl(p)
    p.write_text("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid x\n")
    with pytest.raises(MeshError, match=r"line 7: facet 0 has 2 vertices"):
        read_stl(p)
    with pytest.raises(MeshError, match=r"missing\.stl: cannot read"):
        read_stl(tmp_path / "missing.stl")
    p.write_text("solid empty\nendsolid empty\n")
    v, t = read_stl(p)
    assert v.shape == (0, 3) and t.shape == (0, 3)


def test_interop_is_an_attribute_in_a_fresh_process():
    code = "import topomesh; print(topomesh._interop.from_trimesh.__name__, topomesh.repair.__name__)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["from_trimesh", "repair"]
