"""PLY: what plyfile and trimesh read of topomesh's files, the uniform reader
(gathered straight from the file) against the whole-file read, every binary
vertex layout, mixed face sizes through the record walk, truncated, padded
and long-header files."""

from __future__ import annotations

import numpy as np
import pytest

from topomesh import Mesh, MeshError
from topomesh import io as tio
from tests.io_corpus import CORPUS, T, _same


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
