"""Printing and exchange: binary STL and 3MF files, ``printable()`` and the
wall thickness behind it, and ``topomesh convert`` into these formats."""

from __future__ import annotations

import math
import os
import sys
import warnings

import numpy as np
import pytest

import topomesh as T
from topomesh import GeometryWarning, Mesh, MeshError, cli
from topomesh import io as tio

trimesh = pytest.importorskip("trimesh")


def block(x: float, y: float, z: float) -> Mesh:
    """The box [0, x] × [0, y] × [0, z] as six outward quads."""
    v = np.array([[x * (i & 1), y * ((i >> 1) & 1), z * ((i >> 2) & 1)] for i in range(8)], float)
    f = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    return Mesh.from_polygons(v, f)


SHAPES = {
    "cube": T.cube(),
    "torus": T.torus(8, 6),
    "genus3": T.genus_surface(3),
    "sponge2": T.menger_sponge(2),
    "sierpinski_tet2_doo_sabin": T.tetrahedron().sierpinski(2).doo_sabin(),
    "dodeca_menger1": T.dodecahedron().menger(1),
}


def triangle_mesh(m: Mesh) -> tuple[np.ndarray, np.ndarray]:
    """The triangles as written: used points of ``triangulate()`` and the triangles over them."""
    v, t, _ = m.triangulate()
    used = np.unique(t)
    return v[used], np.searchsorted(used, t)


# ------------------------------------------------------------------ STL


@pytest.mark.parametrize("name", list(SHAPES))
def test_binary_stl_round_trip_and_peer(tmp_path, name):
    m = SHAPES[name]
    v, t = triangle_mesh(m)
    p = tmp_path / f"{name}.stl"
    m.save(p)
    data = p.read_bytes()
    # binary layout: 80-byte header, uint32 count, 50 bytes per triangle
    assert len(data) == 84 + 50 * len(t)
    assert int.from_bytes(data[80:84], "little") == len(t)
    assert not data[:80].lstrip().lower().startswith(b"solid")
    back = T.load(p)
    assert (back.n_vertices, back.n_faces, back.genus) == (len(v), len(t), m.genus)
    assert back.face_size_histogram == {3: len(t)}
    # the corners, rounded to float32, in order
    vb, tb, _ = back.triangulate()
    assert np.array_equal(vb[tb], v[t].astype(np.float32).astype(np.float64))
    # a peer reads it as the same closed solid
    tm = trimesh.load(p, force="mesh")
    assert len(tm.faces) == len(t) and tm.is_watertight
    # (the volume of the triangles: non-planar faces enclose a little more or less than their triangles)
    assert tm.volume == pytest.approx(trimesh.Trimesh(v, t, process=False).volume, rel=1e-5)
    # stored facet normals: unit, outward, those of the triangles
    rec = np.frombuffer(data, dtype=[("n", "<f4", (3,)), ("c", "<f4", (3, 3)), ("a", "<u2")], offset=84)
    c = v[t]
    n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    assert np.allclose(rec["n"], n, atol=1e-6)
    assert (rec["a"] == 0).all()


def test_stl_header_is_never_read_as_ascii(tmp_path):
    # readers take a file starting with "solid" for ASCII: ours must not,
    # and a foreign binary file that does is still read by its size
    p = tmp_path / "c.stl"
    T.cube().save(p)
    data = p.read_bytes()
    assert data[:80] == tio.STL_HEADER and not data[:5].lower() == b"solid"
    bad = tmp_path / "solid_header.stl"
    bad.write_bytes(b"solid made by some CAD".ljust(80, b"\0") + data[80:])
    back = T.load(bad)
    assert (back.n_vertices, back.n_faces) == (8, 12)
    # ASCII STL (trimesh's writer) reads to the same triangle mesh
    asc = tmp_path / "ascii.stl"
    asc.write_bytes(trimesh.exchange.stl.export_stl_ascii(T.cube().to_trimesh()).encode())
    assert asc.read_bytes().startswith(b"solid")
    a = T.load(asc)
    assert (a.n_vertices, a.n_faces, a.genus) == (8, 12, 0)


def test_stl_warns_where_the_triangles_are_not_closed(tmp_path):
    # an open cube: its boundary loop
    m = Mesh.from_polygons(T.cube().vertices, [list(f) for f in np.split(T.cube().face_indices, 6)][:5], close_boundaries=True)
    with pytest.warns(GeometryWarning, match=r"o\.stl: the STL triangles are not a closed 2-manifold \(1 boundary loops; 4 triangle sides"):
        m.save(tmp_path / "o.stl")
    assert T.load(tmp_path / "o.stl", close_boundaries=True).n_holes == 1
    # far from the origin, the cube's corners coincide in float32 (spacing 8 at 1e8)
    far = T.cube().with_vertices(T.cube().vertices + 1e8)
    with pytest.warns(GeometryWarning, match=r"vertices that coincide in float32"):
        far.save(tmp_path / "far.stl")
    # 3MF keeps float64: no warning there
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        far.save(tmp_path / "far.3mf")
    vb, tb, _ = T.load(tmp_path / "far.3mf").triangulate()
    v, t = triangle_mesh(far)
    assert np.array_equal(vb[tb], v[t])


def test_raw_sierpinski_pinches(tmp_path):
    # its self-loops have no triangles: the sub-tetrahedra touch at points
    s = T.tetrahedron().sierpinski(2)
    with pytest.warns(GeometryWarning, match=r"the STL triangles .*\(30 pinched vertices"):
        s.save(tmp_path / "s.stl")
    with pytest.raises(MeshError, match="non-manifold"):
        T.load(tmp_path / "s.stl")
    assert T.load(tmp_path / "s.stl", repair=True).n_faces == len(s.triangles())
    r = s.printable(0.01)
    assert not r.ok and not r.watertight and (r.unpaired_sides, r.pinched_vertices) == (0, s.n_self_loops)
    assert "30 pinched vertices" in str(r)
    # smoothed, the joints get a width and it prints
    assert s.doo_sabin().printable(0.01).ok


def test_failed_stl_write_leaves_the_old_file(tmp_path, monkeypatch):
    p = tmp_path / "keep.stl"
    T.cube().save(p)
    before = p.read_bytes()

    def broken(tmp, verts, tris):
        with open(tmp, "wb") as f:
            f.write(b"half")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(tio, "_write_stl", broken)
    with pytest.raises(MeshError, match=r"keep\.stl: cannot write \(No space left on device\)"):
        T.torus().save(p)
    assert p.read_bytes() == before and os.listdir(tmp_path) == ["keep.stl"]


# ------------------------------------------------------------------ 3MF


def test_stl_refuses_coordinates_beyond_float32_and_keeps_the_old_file(tmp_path):
    topomesh = T
    # float32 turned 1e300 into inf: the file was written, then could not be read back
    p = tmp_path / "big.stl"
    topomesh.save(topomesh.cube(), p)
    before = p.read_bytes()
    c = topomesh.cube()
    with pytest.raises(MeshError, match=r"beyond float32's range .* save it as \.ply"):
        topomesh.save(c.with_vertices(c.vertices * 1e39), p)
    assert p.read_bytes() == before
    huge = c.with_vertices(c.vertices * 1e300)
    for ext in (".ply", ".npz", ".obj", ".3mf"):  # the formats it points to keep them
        q = tmp_path / f"big{ext}"
        topomesh.save(huge, q)
        got = topomesh.load(q).vertices
        assert np.array_equal(np.unique(got, axis=0), np.unique(huge.vertices, axis=0)), ext  # 3MF: triangles, own order


@pytest.mark.parametrize("name", list(SHAPES))
def test_3mf_round_trip_and_peer(tmp_path, name):
    m = SHAPES[name]
    v, t = triangle_mesh(m)
    p = tmp_path / f"{name}.3mf"
    m.save(p)
    back = T.load(p)
    assert (back.n_vertices, back.n_faces, back.genus) == (len(v), len(t), m.genus)
    # float64 coordinates survive exactly, triangle by triangle
    vb, tb, _ = back.triangulate()
    assert np.array_equal(vb[tb], v[t])
    tm = trimesh.load(p, force="mesh")
    assert len(tm.faces) == len(t) and tm.is_watertight
    assert tm.volume == pytest.approx(trimesh.Trimesh(v, t, process=False).volume, rel=1e-12)


def test_3mf_without_its_optional_dependencies(tmp_path, monkeypatch):
    p = tmp_path / "keep.3mf"
    T.cube().save(p)
    before = p.read_bytes()
    monkeypatch.setitem(sys.modules, "lxml", None)  # import lxml now fails
    with pytest.raises(MeshError, match=r"keep\.3mf: 3MF is written and read through trimesh.*lxml.*topomesh\[print\]"):
        T.torus().save(p)
    with pytest.raises(MeshError, match=r"lxml.*pip install"):
        T.load(p)
    assert p.read_bytes() == before and os.listdir(tmp_path) == ["keep.3mf"]


# ------------------------------------------------------- wall thickness


def test_wall_thickness_of_a_slab():
    for d in (0.5, 0.01, 1e-4):
        m = block(3.0, 2.0, d)
        w = m.wall_thickness()
        big = np.abs(m.face_normals[:, 2]) == 1
        assert np.abs(w[big] - d).max() <= 1e-9
        assert np.abs(w[~big] - np.where(np.abs(m.face_normals[~big, 0]) == 1, 3.0, 2.0)).max() <= 1e-9


def test_wall_thickness_of_a_sponge_is_a_cell():
    for level in (1, 2, 3):
        w = T.menger_sponge(level).wall_thickness()
        side = np.ptp(T.menger_sponge(level).vertices[:, 0])
        assert w.min() == pytest.approx(side / 3**level, abs=1e-9)
        assert np.isfinite(w).all()


def test_wall_thickness_budget_and_arguments():
    s = T.menger_sponge(2)
    T.set_memory_budget(1000)
    try:
        with pytest.raises(MeshError, match="wall_thickness: .*memory budget"):
            s.wall_thickness()
    finally:
        T.set_memory_budget(None)
    for bad in (0, -1.0, math.nan, math.inf):
        with pytest.raises(MeshError, match=r"printable: min_thickness = .* must be a finite number > 0"):
            T.cube().printable(bad)
    with pytest.raises(MeshError, match=r"min_thickness = 'thin'"):
        T.printable(T.cube(), "thin")


# -------------------------------------------------------------- printable


def test_thin_box_is_not_printable():
    m = block(1.0, 1.0, 0.01)
    r = m.printable(0.05)
    assert not r.ok and r.watertight and r.n_self_intersections == 0
    big = np.flatnonzero(np.abs(m.face_normals[:, 2]) == 1)
    assert np.array_equal(r.thin_faces, big)
    assert r.min_thickness_found == pytest.approx(0.01, abs=1e-12) and r.thinnest_face in big
    assert "NOT printable" in str(r) and "thin faces (< 0.05): 2: 0, 1" in str(r)
    assert repr(r).startswith("PrintReport(ok=False") and "thin_faces=2" in repr(r)
    assert block(1.0, 1.0, 0.01).printable(0.005).ok


def test_unit_cube_is_printable():
    m = T.cube().with_vertices((T.cube().vertices + 1) / 2)
    r = T.printable(m, 0.5)
    assert r.ok and r.watertight and r.open_boundaries == 0 and len(r.thin_faces) == 0
    assert r.min_thickness_found == pytest.approx(1.0, abs=1e-12)
    assert str(r).splitlines()[0] == "printable with walls of at least 0.5"
    assert not m.printable(1.5).ok


def test_overlapping_cubes_self_intersect():
    c = T.cube()
    v = np.vstack([c.vertices, c.vertices + 0.5])
    faces = [list(f) for f in np.split(c.face_indices, 6)]
    m = Mesh.from_polygons(v, faces + [[i + 8 for i in f] for f in faces])
    r = m.printable(0.1)
    assert not r.ok and r.watertight and r.n_self_intersections > 0
    assert r.n_crossing_triangle_pairs == len(m.self_intersections())
    # every pair joins a face of one cube to a face of the other
    assert ((r.self_intersections[:, 0] < 6) & (r.self_intersections[:, 1] >= 6)).all()
    assert "self-intersections: " in str(r) and "face pairs" in str(r)


def test_crossing_handle_is_not_printable():
    # a handle from the cube's top face back through the cube to its bottom face
    with pytest.warns(GeometryWarning, match="crossing triangle pairs"):
        m = T.cube().add_handle(0, 1, segments=4, weights=(-2.0, -2.0))
    r = m.printable(0.01)
    assert not r.ok and r.n_self_intersections > 0 and r.watertight


def test_open_mesh_is_not_printable():
    c = T.cube()
    m = Mesh.from_polygons(c.vertices, [list(f) for f in np.split(c.face_indices, 6)][:5], close_boundaries=True)
    r = m.printable(0.1)
    assert not r.ok and not r.watertight and r.open_boundaries == 1 and r.unpaired_sides == 4 and r.pinched_vertices == 0
    assert "closed: NO (1 boundary loops" in str(r)
    assert np.isnan(r.thickness[m.n_faces - 1])  # the hole face is not measured


def test_sponge_walls_against_the_parameter():
    s = T.menger_sponge(2)  # side 2: cells of 2/9
    cell = 2 / 9
    thin = s.printable(0.25)
    assert not thin.ok and thin.watertight and thin.n_self_intersections == 0
    assert thin.min_thickness_found == pytest.approx(cell, abs=1e-9)
    assert np.array_equal(thin.thin_faces, np.flatnonzero(s.wall_thickness() < 0.25))
    assert 0 < len(thin.thin_faces) < s.n_faces
    assert s.printable(0.2).ok
    # one more level: every wall a third of that
    assert T.menger_sponge(3).printable(0.2).min_thickness_found == pytest.approx(cell / 3, abs=1e-9)


# ---------------------------------------------------------------- the CLI


def test_convert_to_and_from_stl_and_3mf(tmp_path, capsys):
    src = tmp_path / "g.npz"
    m = T.genus_surface(2)
    m.save(src)
    stl, tmf, ply = tmp_path / "g.stl", tmp_path / "g.3mf", tmp_path / "g.ply"
    assert cli.main(["convert", str(src), str(stl)]) == 0
    assert cli.main(["convert", str(stl), str(tmf)]) == 0
    assert cli.main(["convert", str(tmf), str(ply)]) == 0
    v, t = triangle_mesh(m)
    back = T.load(ply)
    assert (back.n_vertices, back.n_faces, back.genus) == (len(v), len(t), 2)
    tm = trimesh.load(stl, force="mesh")
    assert tm.is_watertight and len(tm.faces) == len(t)
    assert "STL" in cli.parser().format_help() and "3MF" in cli.parser().format_help()


def test_convert_errors_and_warnings_are_one_line(tmp_path, capsys, monkeypatch):
    c = T.cube()
    open_cube = Mesh.from_polygons(c.vertices, [list(f) for f in np.split(c.face_indices, 6)][:5], close_boundaries=True)
    src = tmp_path / "o.ply"
    open_cube.save(src)
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        assert cli.main(["convert", str(src), str(tmp_path / "o.stl")]) == 0
    err = capsys.readouterr().err
    assert err.startswith("topomesh: warning:") and "boundary loops" in err and len(err.splitlines()) == 1
    monkeypatch.setitem(sys.modules, "networkx", None)
    assert cli.main(["convert", str(src), str(tmp_path / "o.3mf")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("topomesh: error:") and "networkx" in err and "Traceback" not in err
    assert not (tmp_path / "o.3mf").exists()
