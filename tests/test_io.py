"""Lossless exchange (corner twins, .npz, .ply, pickle), OBJ/OFF round trip or
refusal, atomic saves, the OBJ reader on real-world files, zero-copy views.
PLY's own reader and writer are tested in tests/test_ply.py."""

from __future__ import annotations

import copy
import os
import pickle
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import topomesh
from topomesh import GeometryWarning, Mesh, MeshError
from topomesh import io as tio

from tests.io_corpus import CORPUS, EMPTY, NAMES, T, _beach_ball, _same, _two_two_gons


# ------------------------------------------------------------ flat arrays


@pytest.mark.parametrize("name", NAMES)
def test_flat_arrays_with_twins_rebuild_the_same_mesh(name):
    m = CORPUS[name]
    t = m.corner_twins
    assert t.dtype == np.int64 and t.shape == m.face_indices.shape
    _same(m, Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices, twins=t))
    # int32 columns (a PLY file's) are read without an int64 copy: the same mesh
    _same(m, Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices.astype(np.int32), twins=t.astype(np.int32)))
    # twins are symmetric and -1 exactly at boundary sides and point-spheres
    inner = t >= 0
    assert np.array_equal(t[t[inner]], np.flatnonzero(inner))


def test_one_gon_on_a_hole_is_not_a_point_sphere(tmp_path):
    # found by the fuzz target (seed 100, case 27019): a face [1, 0, 1] has a
    # self-loop side left open, capped by a one-gon hole; deleting its other
    # edge leaves a one-gon whose self-loop borders the hole. Its polygon list
    # ([1] with twin "none") is a point-sphere's: -1 and -2 tell them apart.
    m = Mesh.from_flat(np.array([[0.0, 0, 0], [1, 0, 0]]), [3], [1, 0, 1], close_boundaries=True)
    e = next(k for k, (a, b) in enumerate(m.edges.tolist()) if a != b)
    one = m.delete_edge_with_cleanup(e)
    assert (one.n_vertices, one.n_edges, one.n_faces, one.n_holes) == (1, 1, 2, 1)
    assert one.corner_twins.tolist() == [-1]
    point, _, _ = Mesh.from_flat(np.zeros((1, 3)), [1], [0]).create_vertex([1.0, 0.0, 0.0])
    assert point.corner_twins.tolist() == [-2, -2]
    for x in (one, point):
        _same(x, Mesh.from_flat(x.vertices, x.face_sizes, x.face_indices, twins=x.corner_twins))
        _same(x, pickle.loads(pickle.dumps(x)))
        for ext in (".npz", ".ply"):
            x.save(tmp_path / f"x{ext}")
            _same(x, topomesh.load(tmp_path / f"x{ext}"))
    # -2 is only for a lone corner whose vertex is in no other face
    with pytest.raises(MeshError, match=r"twin -2 \(a point-sphere\) but its face has other corners"):
        Mesh.from_flat(np.eye(3), [3], [0, 1, 2], twins=[-2, -2, -2])


@pytest.mark.parametrize(
    "make",
    [
        lambda: T.tetrahedron().sierpinski().catmull_clark(),
        lambda: T.cube().insert_edge(0, 0, 1, 0)[0].sqrt3(),
    ],
)
def test_reproducer_polygon_pairing_was_ambiguous(make):
    m = make()
    # the polygon list alone cannot be paired back (the reported bug) ...
    with pytest.raises(MeshError, match="non-manifold"):
        Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices, allow_multi_edges=True)
    # ... the twins can
    _same(m, Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices, twins=m.corner_twins))


def test_two_two_gons_and_beach_balls():
    m = _two_two_gons()
    m.validate()
    assert (m.n_vertices, m.n_edges, m.n_faces, m.genus) == (2, 2, 2, 0)
    a, b = _beach_ball(1), _beach_ball(2)
    a.validate(), b.validate()
    # same polygon list, different gluing: equality sees the twins
    assert np.array_equal(a.face_indices, b.face_indices) and np.array_equal(a.vertices, b.vertices)
    assert a != b and a == _beach_ball(1)


@pytest.mark.parametrize("dtype", [np.int64, np.int32])
def test_bad_twins_name_corner_and_face(dtype):
    m = T.tetrahedron()
    v, s, i, t = m.vertices, m.face_sizes, m.face_indices.astype(dtype), np.array(m.corner_twins, dtype=dtype)
    bad = t.copy()
    bad[4] = 99
    with pytest.raises(MeshError, match=r"corner 4 of face 1 has twin 99, out of range"):
        Mesh.from_flat(v, s, i, twins=bad)
    bad = t.copy()
    bad[[0, 1]] = bad[[1, 0]]
    with pytest.raises(MeshError, match=r"corner 0 of face 0 .* symmetric"):
        Mesh.from_flat(v, s, i, twins=bad)
    # a symmetric pair running the same way
    bad = t.copy()
    a, b = 0, int(t[0])
    c = next(k for k in range(len(t)) if k not in (a, b) and i[k] == i[a])
    d = int(t[c])
    bad[[a, b, c, d]] = [c, d, a, b]
    with pytest.raises(MeshError, match=r"twins: corner \d+ of face \d+ .*opposite directions"):
        Mesh.from_flat(v, s, i, twins=bad)
    with pytest.raises(MeshError, match=r"twins: 11 entries for 12 face indices"):
        Mesh.from_flat(v, s, i, twins=t[:-1])
    with pytest.raises(MeshError, match=r"corner 3 of face 1 is its own twin"):
        Mesh.from_flat(v, s, i, twins=np.where(np.arange(12) == 3, 3, t))


def _built(build):
    """``build()``'s mesh, or the message of the MeshError it raised."""
    try:
        return build()
    except MeshError as e:
        return str(e)


@pytest.mark.parametrize("name", NAMES)
def test_int32_polygons_build_what_int64_polygons_build(name):
    """int32 face arrays (a foreign PLY file's, pyvista's and others') are read
    in place: the same mesh, or the same refusal, from flat indices without
    twins and from (F, k) C-order arrays as from int64; Fortran-order and
    strided int32 arrays take the int64 path and agree too."""
    m = CORPUS[name]
    v, s, i = m.vertices, m.face_sizes, m.face_indices
    for multi in (False, True):
        ref = _built(lambda: Mesh.from_flat(v, s, i, allow_multi_edges=multi))
        assert _built(lambda: Mesh.from_flat(v, s, i.astype(np.int32), allow_multi_edges=multi)) == ref
        if len(s) and (s == s[0]).all():
            f64 = i.reshape(-1, int(s[0]))
            ref2 = _built(lambda: Mesh.from_polygons(v, f64, allow_multi_edges=multi))
            for f32 in (f64.astype(np.int32), np.asfortranarray(f64.astype(np.int32)), np.repeat(f64.astype(np.int32), 2, axis=0)[::2]):
                assert _built(lambda: Mesh.from_polygons(v, f32, allow_multi_edges=multi)) == ref2


def test_int32_polygons_name_the_bad_index():
    t = T.tetrahedron()
    for bad in (4, -1):
        f = t.face_indices.reshape(-1, 3).astype(np.int32)
        f[1, 2] = bad
        with pytest.raises(MeshError, match=rf"index {bad}") as e32:
            Mesh.from_polygons(t.vertices, f)
        with pytest.raises(MeshError) as e64:
            Mesh.from_polygons(t.vertices, f.astype(np.int64))
        assert str(e32.value) == str(e64.value)
        with pytest.raises(MeshError) as flat32:
            Mesh.from_flat(t.vertices, t.face_sizes, f.reshape(-1))
        assert str(flat32.value) == str(e64.value)


def test_size_sum_overflow_is_a_mesh_error():
    idx = np.zeros(14, dtype=np.int64)
    for twins in (None, np.full(14, -1)):
        with pytest.raises(MeshError, match="add up to more than the 14 face indices"):
            Mesh.from_flat(T.tetrahedron().vertices, [2**63 - 1, 2**63 - 1, 14], idx, twins=twins)


# -------------------------------------------------------- lossless formats


@pytest.mark.parametrize("ext", [".npz", ".ply"])
@pytest.mark.parametrize("name", NAMES)
def test_lossless_formats_round_trip(tmp_path, name, ext):
    m = CORPUS[name]
    p = tmp_path / f"m{ext}"
    m.save(p)
    _same(m, T.load(p))


@pytest.mark.parametrize("name", NAMES)
def test_pickle_and_copy_round_trip(name):
    m = CORPUS[name]
    for proto in range(2, pickle.HIGHEST_PROTOCOL + 1):
        _same(m, pickle.loads(pickle.dumps(m, protocol=proto)))
    assert copy.copy(m) == m and copy.deepcopy(m) == m


def _genus_and_back(m):
    return m.genus, m


def test_meshes_cross_process_boundaries():
    from concurrent.futures import ProcessPoolExecutor
    import multiprocessing

    ms = [CORPUS["tet_sierpinski_cc"], CORPUS["handle_sqrt3"], CORPUS["open_cube"]]
    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as ex:
        out = list(ex.map(_genus_and_back, ms))
    for m, (g, back) in zip(ms, out):
        assert g == m.genus and back == m


# ---------------------------------------------------- OBJ / OFF: polygons


@pytest.mark.parametrize("ext", [".obj", ".off"])
@pytest.mark.parametrize("name", NAMES)
def test_polygon_formats_round_trip_or_refuse(tmp_path, name, ext):
    m = CORPUS[name]
    p = tmp_path / f"m{ext}"
    kw = dict(allow_multi_edges=True, close_boundaries=m.n_holes > 0)
    try:
        pairing = Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices, **kw)
        faithful = pairing == m
    except MeshError:
        faithful = False
    if faithful:
        m.save(p)
        _same(m, T.load(p, **kw))
    else:
        with pytest.raises(MeshError, match=r"save it as \.npz or \.ply"):
            m.save(p)
        assert not p.exists()


def test_open_mesh_in_obj_loads_open(tmp_path):
    m = CORPUS["open_cube"]
    m.save(tmp_path / "o.obj")
    for strict in (dict(close_boundaries=False), dict(boundaries="refuse")):
        with pytest.raises(MeshError, match="boundary edge"):
            T.load(tmp_path / "o.obj", **strict)
    _same(m, T.load(tmp_path / "o.obj"))
    _same(m, T.load(tmp_path / "o.obj", close_boundaries=True))  # the legacy spelling of the default


def test_empty_mesh_in_every_format(tmp_path):
    for ext in tio.SAVE_FORMATS:
        EMPTY.save(tmp_path / f"e{ext}")
        back = T.load(tmp_path / f"e{ext}")
        assert back == EMPTY and back.n_vertices == 0


def test_cli_chain_reads_what_it_writes(tmp_path, capsys):
    from topomesh import cli

    src, mid, out = tmp_path / "t.npz", tmp_path / "s.npz", tmp_path / "c.ply"
    T.tetrahedron().save(src)
    assert cli.main(["sierpinski", str(src), str(mid), "-n", "1"]) == 0
    assert cli.main(["subdivide", str(mid), str(out), "--scheme", "catmull_clark", "-n", "1"]) == 0
    assert cli.main(["info", str(out)]) == 0
    assert T.load(out) == T.tetrahedron().sierpinski().catmull_clark()
    # the same chain into OBJ is refused with a message naming the lossless formats
    assert cli.main(["subdivide", str(mid), str(tmp_path / "c.obj"), "--scheme", "catmull_clark"]) == 2
    assert ".npz or .ply" in capsys.readouterr().err


# ------------------------------------------------------------ atomic saves


@pytest.mark.parametrize("ext", [".npz", ".ply"])
def test_failed_save_leaves_old_file(tmp_path, monkeypatch, ext):
    p = tmp_path / f"keep{ext}"
    T.cube().save(p)
    before = p.read_bytes()
    writer = "_write_npz" if ext == ".npz" else "_write_ply"

    def broken(tmp, mesh, *fields):
        with open(tmp, "wb") as f:
            f.write(b"half a file")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(tio, writer, broken)
    with pytest.raises(MeshError, match=rf"{p.name}: cannot write \(No space left on device\)"):
        T.torus(20, 20).save(p)
    assert p.read_bytes() == before
    assert sorted(os.listdir(tmp_path)) == [p.name]


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs Linux's /proc/self/fd")
def test_save_over_a_large_file_releases_it_in_the_background(tmp_path, monkeypatch):
    """A save over a file of 4 MiB or more keeps the old file open through the
    rename and closes it on a thread (the kernel frees it there): the new file
    is in place, and once the thread is done no descriptor of the old file is
    left, whether the rename succeeded or failed."""
    import threading

    def open_here():
        links = []
        for fd in os.listdir("/proc/self/fd"):
            try:
                links.append(os.readlink(f"/proc/self/fd/{fd}"))
            except OSError:
                pass
        return [f for f in links if f.startswith(str(tmp_path))]

    def settle():
        for th in threading.enumerate():
            if th.name == "topomesh-release":
                th.join()

    real, held = tio._release_in_background, []
    monkeypatch.setattr(tio, "_release_in_background", lambda fd: (held.append(fd), real(fd))[1])
    p = tmp_path / "big.ply"
    p.write_bytes(b"\0" * (tio._RELEASE_FROM + 1))
    m = T.torus(30, 20)
    m.save(p)
    settle()
    assert held[-1] is not None and open_here() == []
    assert T.load(p) == m
    m.save(p)  # over a small file: nothing held
    assert held[-1] is None
    p.write_bytes(b"\0" * (tio._RELEASE_FROM + 1))

    def refused(src, dst):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tio.os, "replace", refused)
    with pytest.raises(MeshError, match=r"big\.ply: cannot write \(Permission denied\)"):
        m.save(p)
    settle()
    assert held[-1] is not None and open_here() == []
    assert p.stat().st_size == tio._RELEASE_FROM + 1 and os.listdir(tmp_path) == ["big.ply"]


def test_interrupted_save_leaves_no_temp_file(tmp_path, monkeypatch):
    p = tmp_path / "k.npz"

    def interrupted(tmp, mesh):
        raise KeyboardInterrupt

    monkeypatch.setattr(tio, "_write_npz", interrupted)
    with pytest.raises(KeyboardInterrupt):
        T.cube().save(p)
    assert os.listdir(tmp_path) == []


def test_file_size_limit_leaves_old_file(tmp_path):
    # a real failure mid-write in every writer (Rust text writer included)
    script = textwrap.dedent(
        f"""
        import os, resource, signal, sys
        import topomesh
        d = {str(tmp_path)!r}
        for ext in (".npz", ".ply", ".obj", ".off"):
            topomesh.cube().save(os.path.join(d, "old" + ext))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))
        big = topomesh.torus(100, 100)
        for ext in (".npz", ".ply", ".obj", ".off"):
            try:
                big.save(os.path.join(d, "old" + ext))
            except topomesh.MeshError as e:
                print(ext, "MeshError", e)
            else:
                print(ext, "saved")
        """
    )
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert len(lines) == 4 and all("MeshError" in ln and "old." in ln and "cannot write" in ln for ln in lines), r.stdout
    assert sorted(os.listdir(tmp_path)) == ["old.npz", "old.obj", "old.off", "old.ply"]
    for ext in (".npz", ".ply", ".obj", ".off"):
        assert T.load(tmp_path / f"old{ext}") == T.cube()


def test_io_errors_name_the_path(tmp_path):
    for ext in tio.SAVE_FORMATS:
        missing_dir = tmp_path / "nope" / f"m{ext}"
        with pytest.raises(MeshError, match=rf"{missing_dir}: cannot write"):
            T.cube().save(missing_dir)
    with pytest.raises(MeshError, match=r"m\.stp: unsupported extension"):
        T.cube().save(tmp_path / "m.stp")
    for ext, junk in [(".ply", b"ply\nformat nonsense\n"), (".npz", b"not a zip"), (".off", b"OFF\n3 1\n")]:
        p = tmp_path / f"junk{ext}"
        p.write_bytes(junk)
        with pytest.raises(MeshError, match=rf"{p}: "):
            T.load(p)
    np.savez(tmp_path / "other.npz", a=np.zeros(3))
    with pytest.raises(MeshError, match=r"not a topomesh \.npz file \(missing format_version"):
        T.load(tmp_path / "other.npz")
    # a mesh error in a file names the file too
    p = tmp_path / "bad.off"
    p.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    with pytest.raises(MeshError, match=rf"{p}: edge \(\d, \d\) of face 0 is a boundary edge"):
        T.load(p, boundaries="refuse")


# ------------------------------------------------------------- OBJ reader

BLENDER_CUBE = """\
# Blender 4.1.1
# www.blender.org
mtllib cube.mtl
o Cube
v 1.000000 1.000000 -1.000000
v 1.000000 -1.000000 -1.000000
v 1.000000 1.000000 1.000000
v 1.000000 -1.000000 1.000000
v -1.000000 1.000000 -1.000000
v -1.000000 -1.000000 -1.000000
v -1.000000 1.000000 1.000000
v -1.000000 -1.000000 1.000000
vn -0.0000 1.0000 -0.0000
vn -0.0000 -0.0000 1.0000
vn -1.0000 -0.0000 -0.0000
vn -0.0000 -1.0000 -0.0000
vn 1.0000 -0.0000 -0.0000
vn -0.0000 -0.0000 -1.0000
vt 0.625000 0.500000
vt 0.375000 0.500000
vt 0.625000 0.750000
vt 0.375000 0.750000
vt 0.875000 0.500000
vt 0.625000 0.250000
vt 0.125000 0.500000
vt 0.375000 0.250000
vt 0.875000 0.750000
vt 0.625000 1.000000
vt 0.625000 0.000000
vt 0.375000 1.000000
vt 0.375000 0.000000
vt 0.125000 0.750000
s 0
usemtl Material
f 1/1/1 5/5/1 7/9/1 3/3/1
f 4/4/2 3/3/2 7/10/2 8/12/2
f 8/13/3 7/11/3 5/6/3 6/8/3
g bottom
f 6/7/4 2/2/4 4/4/4 8/14/4
f 2/2/5 1/1/5 3/3/5 4/4/5
o Back
usemtl Other
f -3//6 -4//6 -8//6 \\
  -7//6
l 1 2 3
l 4 5
"""


def _blender_expected():
    v = np.array([[1, 1, -1], [1, -1, -1], [1, 1, 1], [1, -1, 1], [-1, 1, -1], [-1, -1, -1], [-1, 1, 1], [-1, -1, 1]], float)
    f = [[0, 4, 6, 2], [3, 2, 6, 7], [7, 6, 4, 5], [5, 1, 3, 7], [1, 0, 2, 3], [5, 4, 0, 1]]
    return Mesh.from_polygons(v, f)


@pytest.mark.parametrize("newline", ["\n", "\r\n"])
def test_obj_as_blender_writes_it(tmp_path, newline):
    p = tmp_path / "cube.obj"
    p.write_bytes(BLENDER_CUBE.replace("\n", newline).encode())
    with pytest.warns(GeometryWarning, match=r"cube\.obj: skipped 2 polyline \(l\) and 0 point \(p\) elements"):
        m = T.load(p)
    _same(_blender_expected(), m)


def test_obj_errors_give_path_line_and_index_as_written(tmp_path):
    p = tmp_path / "file.obj"
    lines = [f"v {i} {i * i} 0" for i in range(8)] + ["", "# faces", "f 1 2 3", "f 1 3 4"]
    lines.insert(11, "f 1 2 9")  # line 12
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(MeshError, match=rf"^{p}:12: face index 9 is out of range \(8 vertices\)$"):
        T.load(p)
    p.write_text("v 0 0 0\nv 1 0 0\nf 1 2 -3\n")
    with pytest.raises(MeshError, match=rf"^{p}:3: face index -3 is out of range \(2 vertices before this line\)$"):
        T.load(p)
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")
    with pytest.raises(MeshError, match=rf"^{p}:4: face index 0 is invalid"):
        T.load(p)
    p.write_text("v 0 0 zero\n")
    with pytest.raises(MeshError, match=rf'^{p}:1: vertex coordinate "zero" is not a number'):
        T.load(p)


def test_obj_written_by_trimesh_and_pyvista(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    src = T.icosahedron()
    p = tmp_path / "t.obj"
    tm = trimesh.Trimesh(np.array(src.vertices), src.triangles(), process=False)
    tm.export(p, include_normals=True, include_texture=False)
    back = T.load(p)  # trimesh writes 8 decimals: positions agree to that
    assert np.array_equal(back.face_indices, src.face_indices) and np.allclose(back.vertices, src.vertices, atol=1e-7)
    assert "vn " in p.read_text()
    pv = pytest.importorskip("pyvista")
    q = tmp_path / "p.obj"
    pd = pv.PolyData(np.array(T.cube().vertices), np.array(T.cube().padded_faces))
    pd.save(q)
    back = T.load(q)
    assert back.n_faces == 6 and back.genus == 0
    assert np.allclose(back.vertices, T.cube().vertices)


def test_obj_read_is_exact_float64(tmp_path):
    m = T.torus(7, 5, 1.0 / 3.0, 0.1 + 0.2)
    m.save(tmp_path / "x.obj")
    assert np.array_equal(T.load(tmp_path / "x.obj").vertices, m.vertices)


# ----------------------------------------------------- views and caches


def test_exports_are_read_only_views():
    m = T.torus(30, 20)
    for name in ("vertices", "face_sizes", "face_indices", "corner_twins"):
        a, b = getattr(m, name), getattr(m, name)
        assert np.shares_memory(a, b), name
        assert not a.flags.writeable
        assert a.dtype == (np.float64 if name == "vertices" else np.int64)
        with pytest.raises(ValueError, match="read-only"):
            a[0] = 0
        with pytest.raises(ValueError):
            a.flags.writeable = True
    assert m.vertices.shape == (600, 3)
    keep = m.vertices
    del m  # the view keeps the mesh alive
    assert keep.shape == (600, 3) and np.isfinite(keep).all()


def test_peers_get_copies_of_the_views():
    pytest.importorskip("pyvista")
    m = T.cube()
    pd = m.to_pyvista()
    pd.points[0] = [9.0, 9.0, 9.0]  # VTK ignores NumPy's read-only flag
    assert np.array_equal(m.vertices, T.cube().vertices)


def test_cached_queries_agree():
    m = T.genus_surface(3)
    assert m.genus == m.genus == 3
    assert m.n_components == m.n_components == 1


def test_multi_edges_in_obj_name_the_flag_that_reads_them(tmp_path):
    """A mesh with multi-edges written as OBJ has several face sides on one
    vertex pair; read without ``allow_multi_edges=True`` the error says to
    pass it (an odd count, a real non-manifold edge, gets no such hint)."""
    hinted = 0
    for name in NAMES:
        m = CORPUS[name]
        p = tmp_path / f"{name}.obj"
        try:
            m.save(p)
        except MeshError:
            continue  # no faithful OBJ (test_polygon_formats_round_trip_or_refuse)
        try:
            T.load(p, close_boundaries=m.n_holes > 0)
        except MeshError as e:
            assert "pass allow_multi_edges=True" in str(e) and "is used by" in str(e), str(e)
            _same(m, T.load(p, allow_multi_edges=True, close_boundaries=m.n_holes > 0))
            hinted += 1
    assert hinted >= 1
    tri = tmp_path / "fin.obj"  # three triangles on one edge: no pairing reads it
    tri.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n")
    with pytest.raises(MeshError, match=r"is used by 3 face sides") as info:
        T.load(tri)
    assert "allow_multi_edges" not in str(info.value)
