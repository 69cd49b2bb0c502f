"""Lossless exchange (corner twins, .npz, .ply, pickle), OBJ/OFF round trip or
refusal, atomic saves, the OBJ reader on real-world files, zero-copy views."""

from __future__ import annotations

import copy
import os
import pickle
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import topomesh
from topomesh import GeometryWarning, Mesh, MeshError
from topomesh import io as tio

T = topomesh
EMPTY = Mesh.from_flat(np.zeros((0, 3)), [], [])


def _point_sphere():
    return EMPTY.create_vertex([0.0, 0.0, 0.0])[0]


def _two_two_gons():
    # a sphere of two 2-gons: two edges between vertices 0 and 1
    return Mesh.from_flat([[0.0, 0, 0], [1, 0, 0]], [2, 2], [0, 1, 1, 0], twins=[2, 3, 0, 1])


def _beach_ball(turn: int):
    """Three 2-gons on one vertex pair glued in a 3-cycle: the two cycles
    give two different valid spheres with the same polygon list."""
    a_to_b = [0, 2, 4]  # corner of face i running 0 -> 1
    twins = [0] * 6
    for i in range(3):
        j = (i + turn) % 3
        twins[a_to_b[i]] = 2 * j + 1
        twins[2 * j + 1] = a_to_b[i]
    return Mesh.from_flat([[0.0, 0, 0], [1, 0, 0]], [2, 2, 2], [0, 1] * 3, twins=twins)


def _corpus():
    h = T.cube().insert_edge(0, 0, 1, 0)[0]
    tet1 = T.tetrahedron().sierpinski()
    open_pair = Mesh.from_polygons(np.eye(4)[:, :3], [[0, 1, 2], [0, 2, 3]], close_boundaries=True)
    open_cube = Mesh.from_polygons(T.cube().vertices, _faces(T.cube())[1:], close_boundaries=True)
    return {
        "tetrahedron": T.tetrahedron(),
        "cube": T.cube(),
        "octahedron": T.octahedron(),
        "dodecahedron": T.dodecahedron(),
        "icosahedron": T.icosahedron(),
        "torus": T.torus(6, 4),
        "genus2": T.genus_surface(2),
        "tet_sierpinski1": tet1,
        "tet_sierpinski2": T.tetrahedron().sierpinski(2),
        "cube_sierpinski1": T.cube().sierpinski(),
        "tet_sierpinski_cc": tet1.catmull_clark(),
        "tet_sierpinski_sqrt3": tet1.sqrt3(),
        "tet_sierpinski_ds": tet1.doo_sabin(),
        "oct_sierpinski_cc": T.octahedron().sierpinski().catmull_clark(),
        "handle": h,
        "handle_sqrt3": h.sqrt3(),
        "handle_cc": h.catmull_clark(),
        "handle_ds": h.doo_sabin(),
        "cube_and_point": T.cube().create_vertex([5.0, 5.0, 5.0])[0],
        "point_sphere": _point_sphere(),
        "self_loop_sphere": _point_sphere().insert_edge(0, 0, 0, 0)[0],
        "two_two_gons": _two_two_gons(),
        "beach_ball": _beach_ball(1),
        "open_pair": open_pair,
        "open_cube": open_cube,
        "empty": EMPTY,
        # faces over 255 corners: PLY counts become uint
        "pillow300": Mesh.from_polygons(
            np.c_[np.cos(np.arange(300) / 47.0), np.sin(np.arange(300) / 47.0), np.zeros(300)],
            [list(range(300)), list(range(299, -1, -1))],
        ),
    }


def _faces(m):
    return np.split(np.asarray(m.face_indices), np.cumsum(m.face_sizes)[:-1])


CORPUS = _corpus()
NAMES = sorted(CORPUS)


def _same(a: Mesh, b: Mesh):
    assert b == a
    b.validate()
    assert (b.n_vertices, b.n_edges, b.n_faces, b.n_holes, b.genus) == (a.n_vertices, a.n_edges, a.n_faces, a.n_holes, a.genus)


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


def test_ply_is_read_by_plyfile_and_trimesh(tmp_path):
    from plyfile import PlyData

    for m in (T.cube(), CORPUS["tet_sierpinski1"], CORPUS["pillow300"]):
        p = tmp_path / "m.ply"
        m.save(p)
        ply = PlyData.read(str(p))
        assert np.array_equal(np.concatenate(list(ply["face"]["vertex_indices"])), m.face_indices)
        assert np.array_equal(np.concatenate(list(ply["face"]["corner_twins"])), m.corner_twins)
        assert np.array_equal(np.c_[ply["vertex"]["x"], ply["vertex"]["y"], ply["vertex"]["z"]], m.vertices)
        # uniform faces take the one-frombuffer reader, mixed ones the record walk: both exact
        assert (tio._read_ply_uniform(p) is not None) == (len(set(m.face_sizes.tolist())) == 1)
    trimesh = pytest.importorskip("trimesh")
    T.icosahedron().save(tmp_path / "i.ply")
    tm = trimesh.load(tmp_path / "i.ply", process=False)
    assert np.array_equal(tm.vertices, T.icosahedron().vertices) and tm.is_watertight


def test_uniform_ply_is_gathered_from_the_file_as_from_its_bytes(tmp_path):
    """The uniform reader gathers the columns straight from the file, chunk by
    chunk (``_ply_gather_file``), never reading it whole: the same arrays as
    the gather of the whole file's bytes, over several chunks of the core's
    1 MiB buffers (a 3 MB face element)."""
    from topomesh import _ply

    t = T.torus(300, 200)
    m = Mesh.from_polygons(t.vertices, t.triangles())
    p = tmp_path / "m.ply"
    m.save(p)
    src = _ply._Source(p)
    streamed = _ply._read_uniform(src, *_ply._binary_header(src))
    assert src._data is None  # the file was not read whole
    whole = _ply._Source(p)
    whole.data()
    buffered = _ply._read_uniform(whole, *_ply._binary_header(whole))
    for a, b in zip(streamed[:4], buffered[:4]):
        assert a.dtype == b.dtype and np.array_equal(a, b)
    assert np.array_equal(streamed[0], m.vertices) and np.array_equal(streamed[2], m.face_indices)
    assert np.array_equal(streamed[3], m.corner_twins)


@pytest.mark.parametrize("layout", ["f4 xyz first", "f8 xyz first", "xyz last", "mixed types"])
def test_binary_ply_vertex_layouts_are_gathered_as_plyfile_reads_them(tmp_path, layout):
    """Every scalar vertex layout of a binary little-endian file (trimesh and
    scanners write float32, others put normals or colours first or mix
    types) is gathered column by column from the file, never read whole, and
    gives plyfile's values."""
    from plyfile import PlyData, PlyElement

    from topomesh import _ply

    t = T.torus(12, 8)
    tris = t.triangles()
    fields = {
        "f4 xyz first": [("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("red", "u1"), ("quality", "<f4")],
        "f8 xyz first": [("x", "<f8"), ("y", "<f8"), ("z", "<f8"), ("nx", "<f4")],
        "xyz last": [("red", "u1"), ("nx", "<f4"), ("x", "<f8"), ("y", "<f8"), ("z", "<f8")],
        "mixed types": [("x", "<f4"), ("y", "<f8"), ("z", "<f4"), ("s", "<i2")],
    }[layout]
    rng = np.random.default_rng(1)
    vert = np.empty(len(t.vertices), dtype=fields)
    for name, _ in fields:
        vert[name] = t.vertices[:, "xyz".index(name)] if name in "xyz" else rng.integers(0, 200, len(vert))
    face = np.empty(len(tris), dtype=[("vertex_indices", "<i4", (3,))])
    face["vertex_indices"] = tris
    p = tmp_path / "v.ply"
    PlyData([PlyElement.describe(vert, "vertex"), PlyElement.describe(face, "face")], byte_order="<").write(str(p))
    src = _ply._Source(p)
    verts, sizes, idx, twins, (vp, fp, lists, comments) = _ply._read_uniform(src, *_ply._binary_header(src))
    assert src._data is None  # gathered from the file
    ref = PlyData.read(str(p))["vertex"]
    assert verts.dtype == np.float64 and np.array_equal(verts, np.c_[ref["x"], ref["y"], ref["z"]].astype(np.float64))
    for name, dt in fields:
        assert np.array_equal(vp[name], ref[name]) and (name in "xyz" or vp[name].dtype == np.dtype(dt)), name
    assert np.array_equal(idx, tris.reshape(-1)) and twins is None
    assert T.load(p).n_faces == len(tris)


def _interleaved(data: bool):
    """A torus whose faces alternate between quads and pairs of triangles, so
    the PLY face records change length at almost every face (the byte-scatter
    layout), with vertex, face and corner data when ``data``."""
    t = T.torus(12, 8)
    faces = []
    for i, f in enumerate(t.face_indices.reshape(-1, 4).tolist()):
        faces += [list(f)] if i % 2 else [[f[0], f[1], f[2]], [f[0], f[2], f[3]]]
    sizes = np.array([len(f) for f in faces])
    m = Mesh.from_flat(t.vertices, sizes, np.concatenate(faces))
    if data:
        rng = np.random.default_rng(3)
        m = m.with_attributes(vertex={"temp": rng.random(m.n_vertices)},
                              face={"mat": np.arange(len(sizes)) % 5},
                              corner={"uv": rng.random((int(sizes.sum()), 2))})
    return m


@pytest.mark.parametrize("data", [False, True])
def test_mixed_size_ply_writes_and_reads_back(tmp_path, data):
    """Faces of mixed sizes, interleaved or in a few runs: plyfile reads the
    file, and the core's record walk reads it back exactly, data included."""
    from plyfile import PlyData

    few_runs = T.cube().doo_sabin()  # squares, then triangles: two runs
    if data:
        few_runs = few_runs.with_attributes(face={"mat": np.arange(len(few_runs.face_sizes)) % 2})
    for m in (_interleaved(data), few_runs):
        p = tmp_path / "m.ply"
        m.save(p)
        ply = PlyData.read(str(p))
        assert np.array_equal(np.concatenate(list(ply["face"]["vertex_indices"])), m.face_indices)
        assert np.array_equal(np.concatenate(list(ply["face"]["corner_twins"])), m.corner_twins)
        assert tio._read_ply_uniform(p) is None  # mixed sizes: the record walk reads it
        back = T.load(p)
        _same(m, back)
        for kind in ("vertex_attributes", "face_attributes", "corner_attributes"):
            a, b = getattr(m, kind), getattr(back, kind)
            assert a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


@pytest.mark.parametrize("data", [False, True])
def test_ply_records_equal_plyfiles(tmp_path, data):
    """The core's record layout is byte for byte what plyfile writes for the
    same header and columns (plyfile lays out each face on its own)."""
    from plyfile import PlyData

    for m in (_interleaved(data), T.cube().doo_sabin(), T.torus(6, 4)):
        p = tmp_path / "m.ply"
        m.save(p)
        ply = PlyData.read(str(p))
        q = tmp_path / "plyfile.ply"
        PlyData([ply["vertex"], ply["face"]], text=False, byte_order="<", comments=ply.comments).write(str(q))
        ours, theirs = p.read_bytes(), q.read_bytes()
        end = b"end_header\n"
        assert ours[ours.index(end):] == theirs[theirs.index(end):]


def test_truncated_or_padded_mixed_ply_is_an_error(tmp_path):
    p = tmp_path / "m.ply"
    _interleaved(False).save(p)
    data = p.read_bytes()
    (tmp_path / "cut.ply").write_bytes(data[:-3])
    with pytest.raises(MeshError, match=r"cut\.ply: .*record \d+ is cut off by the end of the file"):
        T.load(tmp_path / "cut.ply")
    (tmp_path / "pad.ply").write_bytes(data + b"\0\0")
    with pytest.raises(MeshError, match=r"pad\.ply: .*2 bytes after the last face record"):
        T.load(tmp_path / "pad.ply")


def test_ply_reads_long_headers_and_names_unreadable_files(tmp_path):
    from topomesh._core import _read_bytes

    t = T.torus(12, 8)
    m = Mesh.from_polygons(t.vertices, t.triangles())
    p = tmp_path / "m.ply"
    m.save(p)
    data = p.read_bytes()
    # a header longer than the 64 KiB the reader probes first (many comments)
    head, body = data.split(b"end_header\n", 1)
    lines = head.split(b"\n")
    long = b"\n".join(lines[:2] + [b"comment " + b"x" * 100] * 1000 + lines[2:]) + b"end_header\n" + body
    assert len(long) - len(body) > 1 << 16
    (tmp_path / "long.ply").write_bytes(long)
    _same(m, T.load(tmp_path / "long.ply"))
    # a uniform file whose records run past its end is not read as uniform
    (tmp_path / "cut.ply").write_bytes(data[:-1])
    with pytest.raises(MeshError, match=r"cut\.ply"):
        T.load(tmp_path / "cut.ply")
    with pytest.raises(MeshError, match=r"nothing\.ply: cannot read"):
        _read_bytes(str(tmp_path / "nothing.ply"))
    with pytest.raises(MeshError, match=r"cannot read"):
        _read_bytes(str(tmp_path))  # a directory


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
