"""Attributes and creases through files (OBJ, PLY, .npz) and the trimesh and
pyvista conversions (issue 15, part 4).

Every round trip compares every attribute (values and dtype) and the creases
per corner and per edge vertex pair, since a rebuild may renumber edges.
"""

from __future__ import annotations

import numpy as np
import pytest

import topomesh as tm
from topomesh import GeometryWarning, MeshError

from tests.open_meshes import mesh as open_mesh


def uv_cube() -> tm.Mesh:
    """The unit cube with a UV island per face: every edge is a seam; faces
    grouped and given materials as an OBJ from Blender would be."""
    c = tm.cube()
    f = np.repeat(np.arange(6), 4)
    square = np.tile([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], (6, 1))
    uv = (0.8 * square + np.stack([f % 3, f // 3], 1)) / 3.0  # islands 1/3 apart, 0.8/3 wide
    return c.with_attributes(
        face={"group": np.array(["top", "top", "side", "side", "", "bottom"]),
              "material": np.array(["red"] * 3 + ["blue"] * 3)},
        corner={"uv": uv},
    )


def decorated(m: tm.Mesh, seed: int = 0) -> tm.Mesh:
    """``m`` with vertex, face and corner attributes of several shapes and
    dtypes, and semi-sharp, infinite and corner creases."""
    rng = np.random.default_rng(seed)
    V, F, C = m.n_vertices, len(m.face_sizes), len(m.face_indices)
    m = m.with_attributes(
        vertex={"color": rng.random((V, 3)), "normal": rng.normal(size=(V, 3)), "height": rng.normal(size=V),
                "pose": rng.normal(size=(V, 5))},
        face={"material": rng.integers(0, 5, F), "big": np.arange(F, dtype=np.int64) * 2**40,
              "weights": rng.random((F, 2, 2)).astype(np.float32), "flag": np.arange(F) % 3 == 0,
              "small": rng.integers(-100, 100, F).astype(np.int8)},
        corner={"uv": rng.random((C, 2)), "w": rng.random(C), "rgb": rng.random((C, 3))},
    )
    return m.with_creases(
        edge_sharpness=rng.choice([0.0, 0.0, 1.5, np.inf], m.n_edges),
        vertex_sharpness=rng.choice([0.0, 0.0, 2.0], V),
    )


def edge_creases(m: tm.Mesh) -> dict:
    """Sharpness by sorted vertex pair (multi-edges: the sorted values)."""
    out: dict = {}
    for (a, b), s in zip(m.edges.tolist(), m.edge_sharpness.tolist()):
        out.setdefault((min(a, b), max(a, b)), []).append(s)
    return {k: sorted(v) for k, v in out.items()}


def assert_same_data(m: tm.Mesh, r: tm.Mesh, skip: tuple = ()) -> None:
    assert np.array_equal(r.vertices, m.vertices)
    assert np.array_equal(r.face_indices, m.face_indices)
    for got, want in ((r.vertex_attributes, m.vertex_attributes), (r.face_attributes, m.face_attributes),
                      (r.corner_attributes, m.corner_attributes)):
        want = {k: v for k, v in want.items() if k not in skip}
        assert sorted(got) == sorted(want)
        for k in want:
            assert got[k].dtype == want[k].dtype, k
            assert got[k].shape == want[k].shape, k
            assert np.array_equal(got[k], want[k]), k
    assert np.array_equal(r._corner_sharpness(), m._corner_sharpness())
    assert np.array_equal(r.vertex_sharpness, m.vertex_sharpness)
    assert edge_creases(r) == edge_creases(m)


MESHES = {
    "cube": tm.cube,  # one face size: the NumPy PLY reader
    "truncated": lambda: tm.cube().vertex_truncation(),  # triangles and octagons: plyfile
    "open": lambda: open_mesh("genus2_three_holes"),
    "open_mixed": lambda: open_mesh("mixed"),
}


# ------------------------------------------------------------------ OBJ


def test_obj_uv_cube_with_seams_groups_and_materials(tmp_path):
    m = uv_cube()
    p = tmp_path / "cube.obj"
    m.save(p)
    text = p.read_text()
    # one vt per distinct UV: 24 corners, 4 per island, no island shares a value
    assert sum(ln.startswith("vt ") for ln in text.splitlines()) == 24
    assert "g top" in text and "usemtl blue" in text
    r = tm.load(p)
    assert_same_data(m, r)
    # the seams are kept: corners of one vertex carry different UVs
    uv = r.corner_attributes["uv"]
    at0 = uv[r.face_indices == 0]
    assert len(np.unique(at0, axis=0)) == 3


def test_obj_shared_uvs_share_vt_rows(tmp_path):
    c = tm.cube()
    uv = c.vertices[:, :2][c.face_indices]  # per-vertex: no seams
    m = c.with_attributes(corner={"uv": uv})
    p = tmp_path / "c.obj"
    m.save(p)
    assert sum(ln.startswith("vt ") for ln in p.read_text().splitlines()) == 4  # x, y in {-1, 1}
    assert np.array_equal(tm.load(p).corner_attributes["uv"], m.corner_attributes["uv"])


def test_obj_normals_and_open_mesh(tmp_path):
    m = open_mesh("genus2_three_holes")
    rng = np.random.default_rng(3)
    C, F = len(m.face_indices), len(m.face_sizes)
    m = m.with_attributes(corner={"normal": rng.normal(size=(C, 3)), "uv": rng.random((C, 3))},
                          face={"group": np.array(["a", "b", "c"])[np.arange(F) // 5 % 3]})
    p = tmp_path / "open.obj"
    m.save(p)
    assert "/" in p.read_text().splitlines()[-1].split()[1]  # f v/vt/vn
    r = tm.load(p)
    assert r.n_boundary_loops == m.n_boundary_loops == 3
    assert_same_data(m, r)


def test_obj_read_blender_style_file(tmp_path):
    p = tmp_path / "b.obj"
    p.write_text(
        "mtllib x.mtl\no Plane\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
        "vt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvt 0.6 0\nvt 1 0\nvt 1 1\nvt 0.6 1\nvn 0 0 1\n"
        "usemtl A\nf 1/1/1 2/2/1 3/3/1 4/4/1\ng right\nusemtl B\nf 2/5/1 5/6/1 6/7/1 3/8/1\n"
    )
    r = tm.load(p)
    uv = r.corner_attributes["uv"]
    # vertex 1 (index 2 in the file is 1-based 2) is on the seam: two UVs
    assert uv[1].tolist() == [0.5, 0.0] and uv[4].tolist() == [0.6, 0.0]
    assert np.array_equal(r.corner_attributes["normal"], np.tile([0.0, 0.0, 1.0], (8, 1)))
    assert r.face_attributes["group"].tolist() == ["Plane", "right"]
    assert r.face_attributes["material"].tolist() == ["A", "B"]
    assert r.n_boundary_loops == 1


def test_obj_partial_vt_is_left_out(tmp_path):
    p = tmp_path / "p.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf 2//1 4//1 3//1\n")
    r = tm.load(p)  # the second face has no texture: no UV for its corners
    assert "uv" not in r.corner_attributes
    assert np.array_equal(r.corner_attributes["normal"], np.tile([0.0, 0, 1], (6, 1)))


def test_obj_index_errors_name_the_line(tmp_path):
    p = tmp_path / "e.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n")
    with pytest.raises(MeshError, match=r"e.obj:5: texture coordinate index 2 is out of range"):
        tm.load(p)


def test_obj_warns_about_what_it_cannot_hold(tmp_path):
    m = decorated(tm.cube())
    with pytest.warns(GeometryWarning, match=r"vertex attribute 'color'.*creases"):
        m.save(tmp_path / "d.obj")
    r = tm.load(tmp_path / "d.obj")
    assert np.array_equal(r.corner_attributes["uv"], m.corner_attributes["uv"])
    assert not r.vertex_attributes and not r.face_attributes


def test_obj_without_data_is_unchanged(tmp_path):
    tm.cube().save(tmp_path / "c.obj")
    text = (tmp_path / "c.obj").read_text()
    assert "vt" not in text and "/" not in text and "g " not in text


# ------------------------------------------------------------------ PLY and NPZ


@pytest.mark.parametrize("ext", [".ply", ".npz"])
@pytest.mark.parametrize("name", sorted(MESHES))
def test_lossless_formats_keep_every_attribute_and_crease(tmp_path, ext, name):
    m = decorated(MESHES[name]())
    p = tmp_path / f"m{ext}"
    m.save(p)
    r = tm.load(p)
    assert_same_data(m, r)
    assert r.n_boundary_loops == m.n_boundary_loops


def test_npz_keeps_string_face_attributes(tmp_path):
    m = uv_cube()
    m.save(tmp_path / "u.npz")
    assert_same_data(m, tm.load(tmp_path / "u.npz"))


def test_ply_leaves_strings_out_with_a_warning(tmp_path):
    m = uv_cube()
    with pytest.warns(GeometryWarning, match=r"face attribute 'group' \(dtype <U6"):
        m.save(tmp_path / "u.ply")
    r = tm.load(tmp_path / "u.ply")
    assert sorted(r.face_attributes) == [] and np.array_equal(r.corner_attributes["uv"], m.corner_attributes["uv"])


def test_ply_properties_other_readers_understand(tmp_path):
    from plyfile import PlyData

    m = decorated(tm.cube())
    m.save(tmp_path / "m.ply")
    ply = PlyData.read(str(tmp_path / "m.ply"))
    v, f = ply["vertex"], ply["face"]
    names = [p.name for p in v.properties]
    assert names[:3] == ["x", "y", "z"] and {"red", "green", "blue", "nx", "ny", "nz", "height", "pose_4", "sharpness"} <= set(names)
    assert np.array_equal(np.c_[v["red"], v["green"], v["blue"]], m.vertex_attributes["color"])
    assert np.array_equal(np.concatenate(list(f["texcoord"])).reshape(-1, 2), m.corner_attributes["uv"])
    assert np.array_equal(f["material"], m.face_attributes["material"])
    assert f["small"].dtype == np.int8 and f["big"].dtype == np.float64  # 2**40 does not fit PLY's int
    assert np.array_equal(np.concatenate(list(f["corner_sharpness"])), m._corner_sharpness())


def test_ply_from_another_writer(tmp_path):
    from plyfile import PlyData, PlyElement

    c = tm.cube()
    vert = np.empty(8, dtype=[("x", "f4"), ("y", "f4"), ("z", "f4"), ("red", "u1"), ("green", "u1"), ("blue", "u1"),
                               ("quality", "f4")])
    for i, k in enumerate("xyz"):
        vert[k] = c.vertices[:, i]
    for k in ("red", "green", "blue"):
        vert[k] = np.arange(8) * 30
    vert["quality"] = np.arange(8) / 8
    uv = np.random.default_rng(0).random((24, 2)).astype("f4")
    face = np.empty(6, dtype=[("vertex_indices", "O"), ("texcoord", "O"), ("label", "i2")])
    face["vertex_indices"] = list(c.face_indices.reshape(6, 4).astype("i4"))
    face["texcoord"] = list(uv.reshape(6, 8))
    face["label"] = np.arange(6) * 3
    PlyData([PlyElement.describe(vert, "vertex"),
             PlyElement.describe(face, "face", val_types={"vertex_indices": "i4", "texcoord": "f4"})], text=True).write(str(tmp_path / "f.ply"))
    r = tm.load(tmp_path / "f.ply")
    assert np.array_equal(r.vertex_attributes["color"], np.repeat(np.arange(8.0)[:, None] * 30, 3, axis=1))
    assert np.array_equal(r.vertex_attributes["quality"], vert["quality"].astype(np.float64))
    assert np.array_equal(r.corner_attributes["uv"], uv.astype(np.float64))
    assert r.face_attributes["label"].tolist() == list(range(0, 18, 3))


def test_triangle_and_off_formats_warn_what_they_drop(tmp_path):
    m = decorated(tm.cube())
    for ext in (".stl", ".off"):
        with pytest.warns(GeometryWarning, match="left out vertex attribute 'color'"):
            m.save(tmp_path / f"m{ext}")


def test_load_repair_leaves_attributes_out(tmp_path):
    uv_cube().save(tmp_path / "u.obj")
    r = tm.load(tmp_path / "u.obj", repair=True)  # repair renumbers and keeps no map
    assert r.n_faces == 6 and not r.corner_attributes and not r.face_attributes


# ------------------------------------------------------------------ trimesh


def test_to_trimesh_attributes_and_back():
    pytest.importorskip("trimesh")
    m = open_mesh("mixed")
    rng = np.random.default_rng(1)
    V, F = m.n_vertices, len(m.face_sizes)
    colour = rng.random((V, 4))
    uv = rng.random((V, 2))
    m = m.with_attributes(vertex={"color": colour, "t": rng.random(V)},
                          face={"id": np.arange(F) * 10, "name": np.array([f"f{i}" for i in range(F)])},
                          corner={"uv": uv[m.face_indices]})
    t = m.to_trimesh()
    _, tri_face = m.triangles(return_faces=True)
    assert np.array_equal(t.face_attributes["id"], (np.arange(F) * 10)[tri_face])
    assert np.array_equal(t.face_attributes["name"], m.face_attributes["name"][tri_face])
    assert np.array_equal(t.vertex_attributes["t"], m.vertex_attributes["t"])
    assert np.array_equal(t.visual.uv, uv)  # seam-free: per vertex
    r = tm.Mesh.from_trimesh(t)
    assert np.array_equal(r.vertex_attributes["color"], colour)
    assert np.array_equal(r.face_attributes["id"], t.face_attributes["id"])
    assert np.array_equal(r.corner_attributes["uv"], uv[np.asarray(t.faces).ravel()])


def test_to_trimesh_vertex_colours_rule():
    pytest.importorskip("trimesh")
    c = tm.cube()
    rgb = np.linspace(0, 1, 24).reshape(8, 3)
    t = c.with_attributes(vertex={"color": rgb}).to_trimesh()
    assert t.visual.kind == "vertex"
    assert np.array_equal(np.asarray(t.visual.vertex_colors)[:, :3], np.round(rgb * 255).astype(np.uint8))
    t = c.with_attributes(vertex={"color": rgb * 1000}).to_trimesh()  # not colours
    assert t.visual.kind is None and np.array_equal(t.vertex_attributes["color"], rgb * 1000)
    back = tm.Mesh.from_trimesh(c.with_attributes(vertex={"colour": rgb}).to_trimesh())
    assert np.allclose(back.vertex_attributes["color"][:, :3], rgb, atol=0.5 / 255)  # through visual.vertex_colors


def test_to_trimesh_leaves_seamed_uvs_out():
    pytest.importorskip("trimesh")
    with pytest.warns(GeometryWarning, match="'uv' .*seams"):
        t = uv_cube().to_trimesh()
    assert t.visual.kind != "texture"
    assert t.face_attributes["group"].tolist()[:4] == ["top"] * 4


def test_to_trimesh_added_points_get_face_means():
    pytest.importorskip("trimesh")
    # a cube face whose two diagonals are edges elsewhere (handles): triangulate adds a point inside it
    m = tm.cube()
    quad = list(m.face_indices[:4])
    for a, b in [(quad[0], quad[2]), (quad[1], quad[3])]:
        off = np.r_[0, np.cumsum(m.face_sizes)]
        rows = [list(m.face_indices[off[k] : off[k + 1]]) for k in range(m.n_faces)]
        fa = next(k for k, r in enumerate(rows) if a in r and b not in r)
        fb = next(k for k, r in enumerate(rows) if b in r and a not in r and k != fa)
        m, _ = m.insert_edge(fa, rows[fa].index(a), fb, rows[fb].index(b))
    verts, tris, tri_face = m.triangulate()
    n = m.n_vertices
    assert len(verts) > n
    a = np.random.default_rng(4).random((n, 2))
    with pytest.warns(GeometryWarning, match="repeated vertex"):  # the handles' faces
        t = m.with_attributes(vertex={"a": a}).to_trimesh()
    got = t.vertex_attributes["a"]
    assert np.array_equal(got[:n], a)
    off = np.r_[0, np.cumsum(m.face_sizes)]
    for p in range(n, len(verts)):
        faces = sorted({int(f) for tri, f in zip(tris, tri_face) if p in tri})
        want = np.mean([a[m.face_indices[off[f] : off[f + 1]]].mean(axis=0) for f in faces], axis=0)
        assert np.allclose(got[p], want)
    inside = next(p for p in range(n, len(verts)) if np.allclose(verts[p], m.vertices[quad].mean(axis=0)))
    assert np.allclose(got[inside], a[quad].mean(axis=0))


def test_from_trimesh_warns_about_unfit_arrays():
    trimesh = pytest.importorskip("trimesh")
    t = trimesh.creation.box()
    t.vertex_attributes["bad"] = np.full(len(t.vertices), np.nan)
    t.face_attributes["short"] = np.zeros(3)
    with pytest.warns(GeometryWarning, match=r"vertex attribute 'bad' \(not finite\); face attribute 'short'"):
        r = tm.Mesh.from_trimesh(t)
    assert not r.vertex_attributes and not r.face_attributes


# ------------------------------------------------------------------ pyvista


def test_to_pyvista_point_and_cell_data_and_back():
    pytest.importorskip("pyvista")
    m = decorated(open_mesh("mixed")).without_data()
    rng = np.random.default_rng(2)
    V, F = m.n_vertices, len(m.face_sizes)
    uv = rng.random((V, 2))
    m = m.with_attributes(vertex={"h": rng.random(V), "rgb": rng.random((V, 3))},
                          face={"id": np.arange(F), "w": rng.random((F, 2, 2))},
                          corner={"uv": uv[m.face_indices]})
    p = m.to_pyvista()
    assert np.array_equal(p.point_data["h"], m.vertex_attributes["h"])
    assert np.array_equal(p.cell_data["id"], np.arange(F))
    assert p.cell_data["w"].shape == (F, 4)
    assert np.array_equal(p.active_texture_coordinates, uv)
    r = tm.Mesh.from_pyvista(p)
    assert np.array_equal(r.vertex_attributes["rgb"], m.vertex_attributes["rgb"])
    assert np.array_equal(r.face_attributes["id"], np.arange(F))
    assert np.array_equal(r.face_attributes["w"], m.face_attributes["w"].reshape(F, 4))
    assert np.array_equal(r.corner_attributes["uv"], m.corner_attributes["uv"])
    assert "uv" not in r.vertex_attributes


def test_to_pyvista_leaves_seamed_uvs_out():
    pytest.importorskip("pyvista")
    with pytest.warns(GeometryWarning, match="'uv' .*seams"):
        p = uv_cube().to_pyvista()
    assert p.active_texture_coordinates is None
    assert p.cell_data["group"].tolist() == ["top", "top", "side", "side", "", "bottom"]


def test_from_pyvista_strips_verts_lines_and_unused_points():
    pv = pytest.importorskip("pyvista")
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [9, 9, 9], [1, 1, 0], [2, 1, 0]], dtype=float)
    poly = pv.PolyData(pts, faces=[3, 0, 1, 2], strips=[4, 2, 1, 4, 5], lines=[2, 0, 3], verts=[1, 3])
    # cells: vert, line, poly, strip
    poly.cell_data["c"] = np.array([100, 200, 7, 8])
    poly.point_data["p"] = np.arange(6.0)
    r = tm.Mesh.from_pyvista(poly)
    assert len(r.face_sizes) == 3  # the triangle, then the strip's two triangles
    assert r.face_attributes["c"].tolist() == [7, 8, 8]
    assert r.vertex_attributes["p"].tolist() == [0, 1, 2, 4, 5]  # point 3 is in no face
    assert np.array_equal(r.vertices, pts[[0, 1, 2, 4, 5]])


def test_conversions_without_attributes_add_none():
    pytest.importorskip("trimesh")
    pytest.importorskip("pyvista")
    c = tm.cube()
    t = c.to_trimesh()
    assert not t.vertex_attributes and not t.face_attributes
    r = tm.Mesh.from_pyvista(c.to_pyvista())
    assert not r.vertex_attributes and not r.face_attributes and not r.corner_attributes


@pytest.mark.parametrize("ext", [".ply", ".npz"])
def test_point_sphere_creases_and_face_data(tmp_path, ext):
    m, _, _ = tm.cube().create_vertex([5.0, 5.0, 5.0])  # a point-sphere: a lone corner
    F = len(m.face_sizes)
    m = m.with_attributes(vertex={"a": np.arange(m.n_vertices * 1.0)}, face={"f": np.arange(F)})
    m = m.with_creases(edge_sharpness=np.r_[np.zeros(m.n_edges - 1), 2.0], vertex_sharpness={8: 3.0})
    m.save(tmp_path / f"p{ext}")
    assert_same_data(m, tm.load(tmp_path / f"p{ext}"))


def test_ply_names_that_cannot_be_properties(tmp_path):
    c = tm.cube().with_attributes(vertex={"has space": np.zeros(8), "x": np.ones(8), "ok": np.arange(8.0)})
    with pytest.warns(GeometryWarning, match=r"'has space' .*; vertex attribute 'x' \(its name"):
        c.save(tmp_path / "n.ply")
    assert list(tm.load(tmp_path / "n.ply").vertex_attributes) == ["ok"]
