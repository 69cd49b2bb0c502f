"""Open meshes as first-class input (issue 15, part 1): the constructors'
boundary policy, the boundary queries and χ with boundaries, exports and files
that keep the holes open as the peers see them, and the boundary behaviour of
honeycomb, vertex truncation, Sierpinski, Menger and the rind."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import trimesh

import topomesh
from topomesh import GeometryWarning, Mesh, MeshError
from tests.open_meshes import BUILDERS, EXPECTED, FOUR, mesh, n_edge_loops, sorted_edges, trimesh_boundary_edges

ALL = tuple(BUILDERS)


def face_lists(m: Mesh) -> list[list[int]]:
    return [list(map(int, f)) for f in np.split(m.face_indices, np.cumsum(m.face_sizes)[:-1])] if len(m.face_sizes) else []


def sides_without_reverse(faces) -> set[tuple[int, int]]:
    """Directed face sides whose reverse no face has: the boundary, computed
    from the polygon list alone."""
    sides = {(f[i], f[(i + 1) % len(f)]) for f in faces for i in range(len(f))}
    return {(a, b) for a, b in sides if (b, a) not in sides}


def real_faces(m: Mesh) -> int:
    return m.n_faces - m.n_holes


# ------------------------------------------------------------------ policy


def test_open_input_is_kept_by_default_everywhere(tmp_path):
    v, f = BUILDERS["annulus"]()
    v0, f0 = v.copy(), [list(x) for x in f]
    m = Mesh.from_polygons(v, f)
    assert np.array_equal(v, v0) and f == f0  # the input is untouched
    assert (m.is_closed, m.n_boundary_loops, m.n_holes) == (False, 2, 2)
    assert "boundary_loops=2" in repr(m)
    sizes = [len(x) for x in f]
    flat = np.concatenate(f)
    same = [
        Mesh.from_polygons(v, f, close_boundaries=True),  # the legacy spelling of the default
        Mesh.from_polygons(v, f, boundaries="keep"),
        Mesh.from_flat(v, sizes, flat),
        Mesh.from_flat(v, m.face_sizes, m.face_indices, twins=m.corner_twins),
        Mesh.from_trimesh(trimesh.Trimesh(v, m.triangles(), process=False)),
        topomesh.repair(v, f)[0],
    ]
    for other in same[:4]:
        assert other == m
    for other in same[4:]:
        assert (other.n_boundary_loops, other.euler_characteristic, other.genus) == (2, 0, 0)
    m.save(tmp_path / "a.obj")
    assert topomesh.load(tmp_path / "a.obj") == m
    assert topomesh.load(tmp_path / "a.obj", repair=True).n_boundary_loops == 2


def test_pyvista_open_surface_is_kept():
    pv = pytest.importorskip("pyvista")
    m = mesh("cylinder")
    back = Mesh.from_pyvista(m.to_pyvista())
    assert back == m
    with pytest.raises(MeshError, match="boundary edge"):
        Mesh.from_pyvista(m.to_pyvista(), boundaries="refuse")
    # a pyvista-made open surface: a plane is a quad grid with one boundary loop
    plane = Mesh.from_pyvista(pv.Plane(i_resolution=3, j_resolution=2))
    assert (plane.n_boundary_loops, plane.euler_characteristic, len(plane.boundary_edges())) == (1, 1, 10)


@pytest.mark.parametrize("strict", [dict(close_boundaries=False), dict(boundaries="refuse")])
def test_refusing_names_the_boundary(tmp_path, strict):
    v, f = BUILDERS["disk"]()
    with pytest.raises(MeshError, match=r"edge \(\d+, \d+\) of face \d+ is a boundary edge .*boundaries=\"keep\""):
        Mesh.from_polygons(v, f, **strict)
    with pytest.raises(MeshError, match="boundary edge"):
        Mesh.from_flat(v, [len(x) for x in f], np.concatenate(f), **strict)
    with pytest.raises(MeshError, match="boundary edge"):
        topomesh.repair(v, f, **strict)
    m = Mesh.from_polygons(v, f)
    # the exact rebuild (corner twins: .npz, topomesh's .ply) refuses too
    with pytest.raises(MeshError, match=r"from_flat: the mesh is open \(1 boundary loop, e\.g\. boundary edge"):
        Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices, twins=m.corner_twins, **strict)
    for ext in (".npz", ".ply", ".obj", ".off"):
        m.save(tmp_path / f"d{ext}")
        with pytest.raises(MeshError, match=rf"d\{ext}: .*(boundary edge|the mesh is open)"):
            topomesh.load(tmp_path / f"d{ext}", **strict)
    with pytest.raises(MeshError, match="boundary edge"):
        Mesh.from_trimesh(m.to_trimesh(), **strict)
    # closed meshes pass the strict check
    c = topomesh.cube()
    assert Mesh.from_flat(c.vertices, c.face_sizes, c.face_indices, twins=c.corner_twins, **strict) == c


def test_bad_boundary_options():
    v, f = BUILDERS["disk"]()
    with pytest.raises(MeshError, match=r'from_polygons: boundaries = "close" is not an option; allowed: "keep" .* or "refuse"'):
        Mesh.from_polygons(v, f, boundaries="close")
    with pytest.raises(MeshError, match=r"from_flat: close_boundaries=True .* contradicts boundaries=\"refuse\""):
        Mesh.from_flat(v, [len(x) for x in f], np.concatenate(f), close_boundaries=True, boundaries="refuse")
    with pytest.raises(MeshError, match=r"from_trimesh: boundaries = \"\" is not an option"):
        Mesh.from_trimesh(trimesh.creation.box(), boundaries="")
    with pytest.raises(MeshError, match=r"repair: close_boundaries=True .* contradicts"):
        topomesh.repair(v, f, close_boundaries=True, boundaries="refuse")
    with pytest.raises(TypeError):
        Mesh.from_polygons(v, f, boundaries=1)


# ------------------------------------------------------------------ queries


@pytest.mark.parametrize("name", ALL)
def test_counts_and_euler_characteristic_with_boundaries(name):
    v, f = BUILDERS[name]()
    m = Mesh.from_polygons(v, f)
    m.validate()
    chi, b, g = EXPECTED[name]
    assert (m.euler_characteristic, m.n_boundary_loops, m.genus, m.n_components) == (chi, b, g, 1)
    # χ = V − E + F over the real faces, E counted from the polygon list
    edges = {tuple(sorted(s)) for x in f for s in zip(x, x[1:] + x[:1])}
    assert m.euler_characteristic == len(v) - len(edges) + len(f) == 2 - 2 * m.genus - m.n_boundary_loops
    assert (m.n_edges, real_faces(m)) == (len(edges), len(f))
    assert (m.component_euler_characteristics, m.component_boundary_loops, m.component_genera) == ([chi], [b], [g])
    assert not m.is_closed


@pytest.mark.parametrize("name", ALL)
def test_boundary_loops_and_edges(name):
    v, f = BUILDERS[name]()
    m = Mesh.from_polygons(v, f)
    want = sides_without_reverse(f)
    loops = m.boundary_loops()
    edges = m.boundary_edges()
    assert edges.dtype == np.int64 and edges.shape == (len(want), 2)
    assert {tuple(e) for e in edges.tolist()} == want  # directed as in the faces
    assert len(loops) == m.n_boundary_loops and sum(len(lp) for lp in loops) == len(want)
    from_loops = []
    for lp in loops:
        assert lp.dtype == np.int64 and lp[0] == lp.min() and len(set(lp.tolist())) == len(lp)
        from_loops += [(int(a), int(b)) for a, b in zip(lp, np.roll(lp, -1))]
    assert from_loops == [tuple(e) for e in edges.tolist()]  # the same order, loop after loop
    assert [lp[0] for lp in loops] == sorted(lp[0] for lp in loops)


def test_boundary_orientation_of_an_upward_grid():
    # faces counter-clockwise seen from +z: the boundary runs counter-clockwise too,
    # along the sides of the faces (0 -> 1 -> 2 ... on the bottom row)
    n = 3
    m = mesh("quad_grid", n)
    lp = m.boundary_loops()[0]
    assert lp[:n + 1].tolist() == list(range(n + 1))
    xy = m.vertices[lp][:, :2]
    area = 0.5 * np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1])
    assert area == pytest.approx(1.0)


def test_closed_meshes_are_unchanged():
    for c in (topomesh.cube(), topomesh.torus(), topomesh.genus_surface(3)):
        assert c.is_closed and c.n_boundary_loops == 0 and c.boundary_loops() == []
        assert c.boundary_edges().shape == (0, 2)
        chi = c.n_vertices - c.n_edges + c.n_faces
        assert c.euler_characteristic == chi == 2 - 2 * c.genus
        assert c.component_euler_characteristics == [chi] and c.component_boundary_loops == [0]
        assert "boundary_loops" not in repr(c)


def test_per_component_identity():
    # one mesh of several pieces: the four open fixtures, a closed torus and a closed cube
    parts = [BUILDERS[n]() for n in FOUR] + [(np.array(c.vertices) + 10.0, face_lists(c)) for c in (topomesh.torus(8, 6), topomesh.cube())]
    verts, faces, base = [], [], 0
    for k, (v, f) in enumerate(parts):
        verts.append(np.asarray(v) + [0.0, 0.0, 5.0 * k])
        faces += [[base + i for i in x] for x in f]
        base += len(v)
    m = Mesh.from_polygons(np.vstack(verts), faces)
    m.validate()
    chi, b, g = m.component_euler_characteristics, m.component_boundary_loops, m.component_genera
    assert len(chi) == len(b) == len(g) == m.n_components == len(parts)
    for c, bc, gc in zip(chi, b, g):
        assert c == 2 - 2 * gc - bc
    assert sorted(zip(chi, b, g)) == sorted([EXPECTED[n] for n in FOUR] + [(0, 0, 1), (2, 0, 0)])
    assert sum(chi) == m.euler_characteristic and sum(b) == m.n_boundary_loops and sum(g) == m.genus
    # the loops of each component lie in that component
    label = np.full(m.n_vertices, -1)
    for k, (v, _) in enumerate(parts):
        start = sum(len(p[0]) for p in parts[:k])
        label[start : start + len(v)] = k
    per = np.bincount([label[lp[0]] for lp in m.boundary_loops()], minlength=len(parts))
    assert sorted(per.tolist()) == sorted(b)


# ------------------------------------------------------- peers and files


@pytest.mark.parametrize("name", ALL)
def test_trimesh_and_pyvista_see_the_same_open_mesh(name):
    m = mesh(name)
    tm = m.to_trimesh()
    assert not tm.is_watertight and tm.is_winding_consistent
    assert trimesh_boundary_edges(tm) == sorted_edges(m.boundary_edges())
    assert n_edge_loops(trimesh_boundary_edges(tm)) == m.n_boundary_loops
    assert tm.euler_number == m.euler_characteristic
    from topomesh.gallery import peer_summary  # `topomesh info` and the gallery table

    row = peer_summary(m)
    assert (row["trimesh_watertight"], row["trimesh_genus"]) == (False, m.genus)
    pv = pytest.importorskip("pyvista")
    poly = m.to_pyvista()
    assert isinstance(poly, pv.PolyData) and poly.n_cells == real_faces(m)
    rim = poly.extract_feature_edges(boundary_edges=True, feature_edges=False, manifold_edges=False, non_manifold_edges=False)
    assert rim.n_cells == len(m.boundary_edges())


@pytest.mark.parametrize("name", FOUR)
def test_manifold3d_refuses_open_meshes(name):
    pytest.importorskip("manifold3d")
    m = mesh(name)
    with pytest.raises(MeshError, match=r"to_manifold: the mesh is open \(\d boundary loops?, e\.g\. boundary edge \(\d+, \d+\)\); manifold3d holds closed solids"):
        m.to_manifold()


def _loops(m: Mesh) -> list[list[int]]:
    return [lp.tolist() for lp in m.boundary_loops()]


@pytest.mark.parametrize("name", ALL)
@pytest.mark.parametrize("ext", [".npz", ".ply", ".obj", ".off"])
def test_files_keep_the_holes_open(tmp_path, name, ext):
    m = mesh(name)
    p = tmp_path / f"m{ext}"
    m.save(p)
    back = topomesh.load(p)
    assert back == m
    assert _loops(back) == _loops(m) and back.euler_characteristic == m.euler_characteristic
    # peers reading the file see it open, with the same boundary
    if ext == ".obj":
        tm = trimesh.load(p, process=False, force="mesh")
        assert not tm.is_watertight
        assert trimesh_boundary_edges(tm) == sorted_edges(m.boundary_edges())
    elif ext in (".ply", ".off"):
        # trimesh reads one PLY face list only and no OFF of mixed face sizes:
        # plyfile and the OFF text itself give the polygons
        if ext == ".ply":
            from plyfile import PlyData

            faces = [list(map(int, x)) for x in PlyData.read(str(p))["face"]["vertex_indices"]]
        else:
            rows = [r.split() for r in p.read_text().splitlines() if r.strip() and not r.startswith("#")]
            nv, nf = map(int, rows[1][:2])
            faces = [list(map(int, r[1 : 1 + int(r[0])])) for r in rows[2 + nv : 2 + nv + nf]]
        assert sides_without_reverse(faces) == {tuple(e) for e in m.boundary_edges().tolist()}


@pytest.mark.parametrize("name", FOUR)
def test_stl_reloads_open(tmp_path, name):
    # STL is a triangle soup: the reader welds its corners, and the open mesh comes back open
    m = mesh(name)
    p = tmp_path / "m.stl"
    with pytest.warns(GeometryWarning, match=rf"{m.n_boundary_loops} boundary loops"):
        m.save(p)
    for back in (topomesh.load(p), topomesh.load(p, repair=True)):
        assert (back.n_boundary_loops, back.euler_characteristic, back.genus) == (m.n_boundary_loops, m.euler_characteristic, m.genus)
        assert sorted(len(lp) for lp in back.boundary_loops()) == sorted(len(lp) for lp in m.boundary_loops())
        a = back.vertices[np.concatenate(back.boundary_loops())]
        b = m.vertices[np.concatenate(m.boundary_loops())]
        d = np.linalg.norm(a[:, None] - b[None], axis=2)
        assert len(a) == len(b) and d.min(axis=0).max() < 1e-6 and d.min(axis=1).max() < 1e-6  # float32 in STL


def test_pickle_keeps_holes():
    import pickle

    m = mesh("genus2_three_holes")
    back = pickle.loads(pickle.dumps(m))
    assert back == m and _loops(back) == _loops(m)


# -------------------------------------------- schemes without smoothing


def _check_refined(m: Mesh, out: Mesh, rectified: bool = False) -> None:
    out.validate()
    V, E, F = m.n_vertices, m.n_edges, real_faces(m)
    want = (E, 2 * E, F + V) if rectified else (2 * E, 3 * E, F + V)
    assert (out.n_vertices, out.n_edges, real_faces(out)) == want
    assert (out.n_boundary_loops, out.euler_characteristic, out.genus) == (m.n_boundary_loops, m.euler_characteristic, m.genus)
    assert out.component_euler_characteristics == m.component_euler_characteristics
    # the peers see the same number of boundary loops
    tm = out.to_trimesh()
    assert not tm.is_watertight
    assert n_edge_loops(trimesh_boundary_edges(tm)) == out.n_boundary_loops
    assert trimesh_boundary_edges(tm) == sorted_edges(out.boundary_edges())


@pytest.mark.parametrize("name", FOUR + ("mixed",))
def test_honeycomb_keeps_holes(name):
    m = mesh(name)
    out = m.honeycomb()
    _check_refined(m, out)
    # each loop keeps its length, and its new vertices lie on the old boundary edges
    assert sorted(len(lp) for lp in out.boundary_loops()) == sorted(len(lp) for lp in m.boundary_loops())
    old = m.vertices[m.boundary_edges()]
    mids = old.mean(axis=1)
    new = out.vertices[np.concatenate(out.boundary_loops())]
    d = np.linalg.norm(new[:, None] - mids[None], axis=2).min(axis=1)
    assert d.max() < 1e-12
    two = m.honeycomb(iterations=2, t=0.3)
    _check_refined(out, two)  # counts from the first level's (F real faces)


@pytest.mark.parametrize("name", FOUR + ("mixed",))
def test_vertex_truncation_keeps_holes(name):
    m = mesh(name)
    out = m.vertex_truncation()
    _check_refined(m, out)
    # a boundary loop of n edges becomes one of 2n: its corners are cut off
    assert sorted(len(lp) for lp in out.boundary_loops()) == sorted(2 * len(lp) for lp in m.boundary_loops())
    rect = m.vertex_truncation(mode="polyhedral", ratio=0.5)
    _check_refined(m, rect, rectified=True)
    assert sorted(len(lp) for lp in rect.boundary_loops()) == sorted(len(lp) for lp in m.boundary_loops())
    # the new boundary lies on the old one: cut points at 1/4 and 3/4 of each boundary edge
    old = m.vertices[m.boundary_edges()]
    cuts = np.vstack([0.75 * old[:, 0] + 0.25 * old[:, 1], 0.25 * old[:, 0] + 0.75 * old[:, 1]])
    new = out.vertices[np.concatenate(out.boundary_loops())]
    assert np.linalg.norm(new[:, None] - cuts[None], axis=2).min(axis=1).max() < 1e-12


@pytest.mark.parametrize("name", ALL)
@pytest.mark.parametrize("scheme", ["dual", "simplest"])
def test_later_open_levels_consume_the_previous_bit_for_bit(name, scheme):
    """A multi-level call gives each level after the first its input to
    write over (issue 19: the open dual and simplest reuse its columns); the
    result is the one of a call per level, bit for bit, with vertex
    attributes carried along. (Not √3: its boundary rule alternates with
    the level, so a call per level is not the same subdivision.)"""
    plain = mesh(name)
    # without data the later levels take the given-up path, with data the borrowed one
    for m in (plain, plain.with_attributes(vertex={"w": np.arange(plain.n_vertices, dtype=float)[:, None] * [1.0, -0.5]})):
        three = getattr(m, scheme)(iterations=3)
        step = m
        for _ in range(3):
            step = getattr(step, scheme)()
        assert three.n_holes == step.n_holes == m.n_holes
        pairs = [(three.vertices, step.vertices), (three.face_indices, step.face_indices), (three.corner_twins, step.corner_twins)]
        if m.vertex_attributes:
            pairs.append((three.vertex_attributes["w"], step.vertex_attributes["w"]))
        for a, b in pairs:
            assert a.shape == b.shape and np.array_equal(a.view(np.uint8), b.view(np.uint8))
        three.validate()


@pytest.mark.parametrize("name", FOUR + ("mixed",))
def test_rind_of_an_open_surface_is_its_closed_shell(name):
    m = mesh(name)
    r = m.rind(0.05)
    s = r.mesh
    s.validate()
    g, b = m.genus, m.n_boundary_loops
    assert s.is_closed and (s.n_components, s.euler_characteristic, s.genus) == (1, 2 * m.euler_characteristic, 2 * g + b - 1)
    assert r.punched == sorted(range(m.n_faces - b, m.n_faces)) and r.n_outer_faces == m.n_faces
    # each loop of n edges became a strip of n quads; the real faces' twins are still there to punch
    assert s.n_faces == 2 * real_faces(m) + m.boundary_edges().shape[0]
    assert r.face_pair(0) is not None and r.face_pair(m.n_faces - 1) is None
    tm = s.to_trimesh()
    assert tm.is_watertight and tm.is_winding_consistent and tm.volume > 0
    pytest.importorskip("manifold3d")
    assert s.to_manifold().genus() == s.genus
    # the rim: outer boundary vertices keep their place, inner ones moved along the averaged normal
    np.testing.assert_array_equal(s.vertices[: m.n_vertices], m.vertices)


@pytest.mark.parametrize("name", FOUR)
def test_sierpinski_and_menger_refuse_open_meshes(name):
    m = mesh(name)
    b = m.n_boundary_loops
    loops = rf"the mesh has {b} boundary loops? \(it is open: boundary edge \(\d+, \d+\), \.\.\.\)"
    with pytest.raises(MeshError, match=rf"^sierpinski: {loops}; Sierpinski's rule .* has no boundary version: .*pinch"):
        m.sierpinski()
    with pytest.raises(MeshError, match=rf"^menger: {loops}; the generalized sponge .* no rule for the rim"):
        m.menger()
    # zero iterations is the identity, open or not
    assert m.sierpinski(iterations=0) == m


def test_cli_subdivides_an_open_mesh(tmp_path, capsys):
    from topomesh import cli

    src, out = tmp_path / "c.obj", tmp_path / "h.ply"
    mesh("cylinder").save(src)
    assert cli.main(["subdivide", str(src), str(out), "--scheme", "honeycomb"]) == 0
    h = topomesh.load(out)
    assert (h.n_boundary_loops, h.euler_characteristic) == (2, 0)
    assert cli.main(["sierpinski", str(src), str(tmp_path / "s.obj")]) == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert last.startswith("topomesh: error: sierpinski: the mesh has 2 boundary loops"), last


def test_fixtures_render_sensibly():
    # no coincident vertices, no degenerate faces: geometry a user would draw
    for name in ALL:
        m = mesh(name)
        v = m.vertices
        d = np.linalg.norm(v[:, None] - v[None], axis=2) + np.eye(len(v)) * 1e9
        assert d.min() > 1e-3, name
        verts, tris, _ = m.triangulate()
        c = verts[tris]
        area = 0.5 * np.linalg.norm(np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]), axis=1)
        assert area.min() > 1e-3, name
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            Mesh.from_polygons(*BUILDERS[name]())  # no inside-out warning


def test_readme_open_meshes_example_runs(tmp_path, monkeypatch):
    import re
    from pathlib import Path

    text = (Path(__file__).parent.parent / "README.md").read_text()
    section = text[text.index("## Open meshes") :]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    scope: dict = {}
    exec(compile(code, "README.md", "exec"), scope)
    assert [len(lp) for lp in scope["loops"]] == [12, 12] and scope["rims"].shape == (24, 2)


def test_vertex_normals_ignore_holes():
    # a flat grid: every vertex normal is +z, boundary ones too (the hole would turn them over)
    m = mesh("quad_grid", 3)
    np.testing.assert_allclose(m.vertex_normals, np.tile([0.0, 0.0, 1.0], (m.n_vertices, 1)), atol=1e-15)
    # the open tube: normals point away from the axis on the rims as in the middle
    t = mesh("cylinder")
    radial = np.array(t.vertices) * [1.0, 1.0, 0.0]
    np.testing.assert_allclose(t.vertex_normals, radial / np.linalg.norm(radial, axis=1, keepdims=True), atol=1e-12)
