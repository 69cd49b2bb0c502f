"""TopMod's remeshing menu and extrusions (src/schemes/topmod/, issue 16).

Every entry's counts are recomputed here from the formulas of its docs
(docs/schemes/topmod.md) and compared with the meshes produced on the cube,
a torus, genus_surface(2), a prism with a non-convex (star) face, and cubes
carrying a two-gon and a self-loop; genus and χ must stay, ``validate()``
must pass, and trimesh must see the closed ones watertight with the same χ.
Known polyhedra give fixed counts (root-3 of the icosahedron is the pentakis
dodecahedron, dual pentagonalization of the cube the snub cube's counts...).
"""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest
import trimesh

import topomesh


def cube_with_two_gon() -> topomesh.Mesh:
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 1)
    assert m.face_size_histogram == {2: 1, 4: 6}
    return m


def cube_with_self_loop() -> topomesh.Mesh:
    m, _ = topomesh.cube().insert_edge(0, 0, 0, 0)
    assert m.n_self_loops == 1 and m.face_size_histogram == {1: 1, 4: 5, 5: 1}
    return m


def star_prism() -> topomesh.Mesh:
    """A prism over a five-pointed star: two non-convex decagons, ten quads."""
    k = np.arange(10)
    r = np.where(k % 2 == 0, 1.0, 0.4)
    a = np.pi * k / 5
    ring = np.c_[r * np.cos(a), r * np.sin(a)]
    v = np.r_[np.c_[ring, np.zeros(10)], np.c_[ring, np.full(10, 0.5)]]
    faces = [list(range(9, -1, -1)), list(range(10, 20))] + [[i, (i + 1) % 10, 10 + (i + 1) % 10, 10 + i] for i in range(10)]
    return topomesh.Mesh.from_polygons(v, faces)


INPUTS = {
    "cube": topomesh.cube,
    "torus": lambda: topomesh.torus(6, 4),
    "genus2": lambda: topomesh.genus_surface(2),
    "star_prism": star_prism,
    "two_gon": cube_with_two_gon,
    "self_loop": cube_with_self_loop,
}
# meshes whose geometry trimesh can judge (no zero-length self-loop, no flat two-gon)
GEOMETRIC = {"cube", "torus", "genus2", "star_prism"}


def H(m):
    return dict(m.face_size_histogram)


def val(m):
    return {k: c for k, c in m.valence_histogram.items() if k > 0}


def add(*hs):
    out: Counter = Counter()
    for h in hs:
        out.update(h)
    return {k: c for k, c in out.items() if c}


def times(h, k):
    return add({k * n: c for n, c in h.items()})


def h3(m):
    return sum(n * c for n, c in H(m).items() if n >= 3)


def vs(m):
    """Valence sum over vertices of valence >= 3."""
    return sum(k * c for k, c in val(m).items() if k >= 3)


def dual_loop_counts(m):
    v, e, f = m.n_vertices, m.n_edges, m.n_faces
    vh = val(m)
    v3 = vh.get(3, 0)
    s = sum(k * c for k, c in vh.items() if k != 3)
    ft, et, vt = v3 + s, e + s, f + v - v3
    return 4 * ft, 2 * et + 3 * ft, vt + et


# name: (call, (V', E', F') from the input, face sizes from the input or None)
ENTRIES = {
    "stellate": (lambda m: m.stellate(offset=0.1), lambda m, v, e, f: (v + f, 3 * e, 2 * e), lambda m, e: {3: 2 * e}),
    "double_stellate": (lambda m: m.double_stellate(offset=0.1), lambda m, v, e, f: (v + f + 2 * e, 9 * e, 6 * e), lambda m, e: {3: 6 * e}),
    "double_stellate_misc": (lambda m: m.double_stellate_misc(height=0.1, curve=0.05), lambda m, v, e, f: (v + f + 2 * e, 6 * e, 3 * e), lambda m, e: {4: 3 * e}),
    "stellate_edge_removal": (lambda m: m.stellate_edge_removal(), lambda m, v, e, f: (v + f, 2 * e, e), lambda m, e: {4: e}),
    "linear_vertex_insertion": (lambda m: m.linear_vertex_insertion(), lambda m, v, e, f: (v + e + f, 4 * e, 2 * e), lambda m, e: {4: 2 * e}),
    "corner_cutting": (lambda m: m.corner_cutting(alpha=0.6), lambda m, v, e, f: (2 * e, 4 * e, f + e + v), lambda m, e: add(H(m), {4: e}, val(m))),
    "modified_corner_cutting": (lambda m: m.modified_corner_cutting(thickness=0.2), lambda m, v, e, f: (2 * e, 4 * e, f + e + v), lambda m, e: add(H(m), {4: e}, val(m))),
    "root3": (lambda m: m.root3(), lambda m, v, e, f: (v + f, 3 * e, 2 * e), lambda m, e: {3: 2 * e}),
    "loop_style": (lambda m: m.loop_style(length=0.5), lambda m, v, e, f: (v + e, 4 * e, f + 2 * e), lambda m, e: add(H(m), {3: 2 * e})),
    "root4": (lambda m: m.root4(weight=0.3, twist=0.2), lambda m, v, e, f: (v + 2 * e, 4 * e, f + e), lambda m, e: add(H(m), {6: e})),
    "dual_loop_style": (lambda m: m.dual_loop_style(), lambda m, v, e, f: (v + 2 * e, 4 * e, f + e), lambda m, e: add(H(m), {6: e})),
    "hexagon_preserving": (lambda m: m.hexagon_preserving(), lambda m, v, e, f: (v + 2 * e, 4 * e, f + e), lambda m, e: add(H(m), {6: e})),
    "dual_hexagon_preserving": (lambda m: m.dual_hexagon_preserving(), lambda m, v, e, f: (v + e, 4 * e, f + 2 * e), lambda m, e: add(H(m), {3: 2 * e})),
    "dual_loop": (lambda m: m.dual_loop(), lambda m, v, e, f: dual_loop_counts(m), None),
    "pentagonalize": (lambda m: m.pentagonalize(offset=0.2), lambda m, v, e, f: (v + 2 * e + f, 5 * e, 2 * e), lambda m, e: {5: 2 * e}),
    "cubic_pentagonalize": (lambda m: m.cubic_pentagonalize(), lambda m, v, e, f: (v + 2 * e + f, 5 * e, 2 * e), lambda m, e: {5: 2 * e}),
    "dual_pentagonalize": (lambda m: m.dual_pentagonalize(), lambda m, v, e, f: (2 * e, 5 * e, v + f + 2 * e), lambda m, e: add(H(m), val(m), {3: 2 * e})),
    "pentagon_preserving": (
        lambda m: m.pentagon_preserving(scale=0.6),
        lambda m, v, e, f: (v + e + h3(m), 2 * e + 2 * h3(m), f + h3(m)),
        lambda m, e: add({n: c for n, c in H(m).items() if n >= 3}, {2 * n: c for n, c in H(m).items() if n < 3}, {5: h3(m)}),
    ),
    "dual_pentagon_preserving": (lambda m: m.dual_pentagon_preserving(), lambda m, v, e, f: (v + vs(m), 2 * e + 2 * vs(m), f + e + vs(m)), None),
    "dual_12_6_4": (lambda m: m.dual_12_6_4(scale=0.7), lambda m, v, e, f: (4 * e, 6 * e, f + e + v), lambda m, e: add(times(H(m), 2), {4: e}, times(val(m), 2))),
    "remesh_12_6_4": (lambda m: m.remesh_12_6_4(), lambda m, v, e, f: (v + e + f, 6 * e, 4 * e), lambda m, e: {3: 4 * e}),
    "checkerboard": (lambda m: m.checkerboard(thickness=0.3), lambda m, v, e, f: (v + 4 * e, 9 * e, f + 4 * e), lambda m, e: add(H(m), {4: 4 * e})),
    "dual_checkerboard": (lambda m: m.dual_checkerboard(), lambda m, v, e, f: (v + 4 * e, 9 * e, f + 4 * e), lambda m, e: add(H(m), {4: 4 * e})),
    "doo_sabin_bc": (lambda m: m.doo_sabin_bc(), lambda m, v, e, f: (4 * e, 8 * e, f + 3 * e + v), lambda m, e: add(times(H(m), 2), {4: 2 * e, 2: e}, val(m))),
    "doo_sabin_bc_new": (lambda m: m.doo_sabin_bc_new(scale=0.8, length=0.5), lambda m, v, e, f: (v + 4 * e, 7 * e, f + 2 * e), lambda m, e: add(times(H(m), 2), {5: 2 * e})),
    "dome": (lambda m: m.dome(), lambda m, v, e, f: (v + 59 * e, 116 * e, f + 56 * e), lambda m, e: add(times(H(m), 4), {4: 56 * e})),
    "fractal": (lambda m: m.fractal(), lambda m, v, e, f: (v + e + f, 6 * e, 4 * e), lambda m, e: {3: 4 * e}),
}


def trimesh_agrees(r: topomesh.Mesh) -> None:
    verts, tris, _ = r.triangulate()
    tm = trimesh.Trimesh(vertices=verts, faces=tris, process=False)
    assert tm.is_watertight and tm.is_winding_consistent
    assert tm.euler_number == r.euler_characteristic


@pytest.mark.parametrize("mesh", list(INPUTS))
@pytest.mark.parametrize("name", list(ENTRIES))
def test_counts_genus_and_validity(name, mesh):
    call, counts, hist = ENTRIES[name]
    m = INPUTS[mesh]()
    before = (m.vertices.copy(), m.face_indices.copy())
    r = call(m)
    r.validate()
    assert (r.n_vertices, r.n_edges, r.n_faces) == counts(m, m.n_vertices, m.n_edges, m.n_faces)
    if hist is not None:
        assert H(r) == hist(m, m.n_edges)
    assert (r.genus, r.euler_characteristic, r.n_components) == (m.genus, m.euler_characteristic, m.n_components)
    assert np.isfinite(r.vertices).all()
    if mesh in GEOMETRIC:
        trimesh_agrees(r)
    assert np.array_equal(m.vertices, before[0]) and np.array_equal(m.face_indices, before[1]), "the input was modified"


@pytest.mark.parametrize("name", ["stellate", "loop_style", "root4", "checkerboard", "pentagonalize"])
def test_iterations_compose(name):
    call = name
    m = topomesh.genus_surface(2)
    two = getattr(m, call)(iterations=2)
    assert two == getattr(getattr(m, call)(), call)()
    assert getattr(m, call)(iterations=0) == m
    with pytest.raises(topomesh.MeshError, match="iterations"):
        getattr(m, call)(iterations=-1)


def test_known_polyhedra():
    ico, cube, dod, octa = topomesh.icosahedron(), topomesh.cube(), topomesh.dodecahedron(), topomesh.octahedron()
    counts = lambda m: (m.n_vertices, m.n_edges, m.n_faces)
    assert counts(ico.root3()) == (32, 90, 60)  # pentakis dodecahedron (dual of the truncated icosahedron)
    assert counts(cube.stellate_edge_removal()) == (14, 24, 12)  # rhombic dodecahedron
    assert val(cube.stellate_edge_removal()) == {3: 8, 4: 6}
    assert counts(cube.stellate()) == (14, 36, 24)  # tetrakis hexahedron
    assert counts(cube.pentagonalize()) == (38, 60, 24)  # pentagonal icositetrahedron
    assert counts(cube.dual_pentagonalize()) == (24, 60, 38) and H(cube.dual_pentagonalize()) == {3: 32, 4: 6}  # snub cube
    assert H(dod.dual_pentagonalize()) == {3: 80, 5: 12}  # snub dodecahedron
    assert H(cube.dual_12_6_4()) == {4: 12, 6: 8, 8: 6}  # truncated cuboctahedron
    assert H(cube.corner_cutting()) == {3: 8, 4: 18}  # rhombicuboctahedron
    assert H(dod.pentagon_preserving()) == {5: 72}
    assert H(octa.loop_style()) == {3: 32}


def test_parameters_are_checked():
    c = topomesh.cube()
    bad = [
        (lambda: c.corner_cutting(alpha=1.0), "alpha"),
        (lambda: c.corner_cutting(alpha=0.2), "alpha"),
        (lambda: c.modified_corner_cutting(thickness=1.5), "thickness"),
        (lambda: c.loop_style(length=-0.1), "length"),
        (lambda: c.root4(twist=1.1), "twist"),
        (lambda: c.root4(weight=float("nan")), "weight"),
        (lambda: c.pentagonalize(offset=2.0), "offset"),
        (lambda: c.pentagon_preserving(scale=1.5), "scale"),
        (lambda: c.dual_12_6_4(scale=0.0), "scale"),
        (lambda: c.checkerboard(thickness=0.6), "thickness"),
        (lambda: c.stellate(offset=float("inf")), "offset"),
        (lambda: c.dome(length=3.0), "length"),
        (lambda: c.fractal(offset=-1.0), "offset"),
        (lambda: c.extrude(0, kind="prism"), "kind"),
        (lambda: c.extrude(0, segments=0), "segments"),
        (lambda: c.extrude(0, kind="stellate", segments=2), "segments"),
        (lambda: c.extrude(0, kind="doo_sabin", twist=2.0), "twist"),
        (lambda: c.extrude(0, scale=0.0), "scale"),
        (lambda: c.extrude([0, 6]), "face 6"),
        (lambda: c.extrude([-1]), "face -1"),
        (lambda: c.subdivide_faces([9]), "face 9"),
        (lambda: c.double_stellate_misc(height=1.5), "height"),
        (lambda: c.double_stellate_misc(curve=-2.0), "curve"),
        (lambda: c.doo_sabin_bc_new(scale=0.0), "scale"),
        (lambda: c.doo_sabin_bc_new(length=1.5), "length"),
        (lambda: c.extrude(0, kind="dodecahedral", angle=181.0), "angle"),
        (lambda: c.extrude(0, kind="icosahedral", lengths=(1.0, 1.0, -1.0)), "lengths"),
        (lambda: c.extrude(0, kind="icosahedral", length=1.0), "length"),
        (lambda: c.extrude(0, kind="cubical", angle=30.0), "angle"),
    ]
    for f, word in bad:
        with pytest.raises(topomesh.MeshError, match=word):
            f()


def test_open_meshes_are_refused():
    quads = [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]]
    grid = topomesh.Mesh.from_polygons(np.c_[np.mgrid[0:3, 0:3].reshape(2, -1).T, np.zeros(9)].astype(float), quads)
    for f in (lambda m: m.stellate(), lambda m: m.root4(), lambda m: m.checkerboard(), lambda m: m.extrude(0)):
        with pytest.raises(topomesh.MeshError, match="boundary loop"):
            f(grid)
    # every remeshing entry refuses under its own name (not that of a step
    # inside a composition, such as root3's dual) and says why, without
    # pointing to boundary rules it does not have; iterations=0 is the input
    for e in topomesh.catalog("topmod"):
        if "iterations" not in (getattr(topomesh.Mesh, e["method"]).__text_signature__ or ""):
            continue
        with pytest.raises(topomesh.MeshError) as info:
            getattr(grid, e["method"])()
        msg = str(info.value)
        assert msg.startswith(f"{e['method']}: the mesh has 1 boundary loop (it is open); {e['method']} takes closed "
                              "meshes only: it has no boundary rule"), msg
        assert "_level" not in msg and "catmull_clark, loop" in msg, msg
        assert getattr(grid, e["method"])(iterations=0) == grid


EXTRUDE = {
    "cubical": (dict(twist=10.0, segments=3, scale=0.9, length=0.5), lambda n, s: (s * n, 2 * s * n, s * n)),
    "doo_sabin": (dict(twist=0.2, segments=2, scale=0.8, length=0.5), lambda n, s: (s * n, 2 * s * n, s * n)),
    "octahedral": (dict(twist=5.0, segments=2, length=0.5), lambda n, s: (s * n, 3 * s * n, 2 * s * n)),
    "stellate": (dict(length=0.5), lambda n, s: (1, n, n - 1)),
    "double_stellate": (dict(length=0.5), lambda n, s: (n + 1, 4 * n, 3 * n - 1)),
    "dome": (dict(twist=1.0), lambda n, s: (5 * n + 1, 11 * n, 6 * n - 1)),
    "dodecahedral": (dict(segments=2), lambda n, s: (3 * s * n, 5 * s * n, 2 * s * n)),
    "icosahedral": (dict(segments=2, angle=45.0, lengths=(0.4, 0.6, 0.7)), lambda n, s: (3 * s * n, 9 * s * n, 6 * s * n)),
}


@pytest.mark.parametrize("mesh", list(INPUTS))
@pytest.mark.parametrize("kind", list(EXTRUDE))
def test_extrusions(kind, mesh):
    kw, added = EXTRUDE[kind]
    m = INPUTS[mesh]()
    sel = list(range(0, m.n_faces, 2)) + [0]
    r = m.extrude(sel, kind=kind, **kw)
    r.validate()
    v, e, f = m.n_vertices, m.n_edges, m.n_faces
    deg = face_degrees(m)
    for x in sorted(set(sel)):
        a, b, c = added(deg[x], kw.get("segments", 1))
        v, e, f = v + a, e + b, f + c
    assert (r.n_vertices, r.n_edges, r.n_faces) == (v, e, f)
    assert (r.genus, r.euler_characteristic) == (m.genus, m.euler_characteristic)
    if mesh in GEOMETRIC:
        trimesh_agrees(r)


def face_degrees(m: topomesh.Mesh) -> list[int]:
    return [int(s) for s in m.face_sizes]


def test_extrusion_geometry():
    c = topomesh.cube()
    area = float(np.linalg.norm(np.cross(*(c.vertices[c.face_indices[1:3]] - c.vertices[c.face_indices[0]]))))
    r = c.extrude(0, length=1.0)
    assert r.volume == pytest.approx(c.volume + area)
    s = c.extrude(0, kind="stellate", length=1.0)
    assert s.volume == pytest.approx(c.volume + area / 3)
    # the default length is TopMod's 2
    d = c.extrude(0)
    assert np.ptp(d.vertices, axis=0).max() == pytest.approx(np.ptp(c.vertices, axis=0).max() + 2.0)


def test_new_entries_shapes():
    # the dodecahedral extrusion of a dodecahedron face and the icosahedral one of
    # an icosahedron face grow the solid by the polyhedron's ring of faces
    dod, ico = topomesh.dodecahedron(), topomesh.icosahedron()
    r = dod.extrude(0, kind="dodecahedral")
    assert H(r) == {5: 12 + 10} and r.volume > dod.volume
    r = ico.extrude(0, kind="icosahedral")
    assert H(r) == {3: 20 + 18} and r.volume > ico.volume
    # the second double stellation is the join of the stellation
    c = topomesh.cube()
    assert c.double_stellate_misc() == c.stellate().stellate_edge_removal()
    # Doo-Sabin BC New keeps the old vertices (length 1) and their valences
    b = c.doo_sabin_bc_new()
    assert np.array_equal(b.vertices[:8], c.vertices)
    assert [b.valence_histogram.get(k, 0) for k in (3,)] == [8 + 48]


@pytest.mark.parametrize("quads", [True, False])
def test_subdivide_faces(quads):
    m = topomesh.genus_surface(2)
    sel = [0, 3, 3, 7]
    r = m.subdivide_faces(sel, quads=quads)
    r.validate()
    deg = face_degrees(m)
    uniq = sorted(set(sel))
    k, n = len(uniq), sum(deg[f] for f in uniq)
    if quads:
        s = len(split_edges(m, uniq))
        assert (r.n_vertices, r.n_edges, r.n_faces) == (m.n_vertices + s + k, m.n_edges + s + n, m.n_faces - k + n)
    else:
        assert (r.n_vertices, r.n_edges, r.n_faces) == (m.n_vertices + k, m.n_edges + n, m.n_faces - k + n)
    assert r.genus == 2
    trimesh_agrees(r)
    assert m.subdivide_faces(list(range(m.n_faces))) == m.linear_vertex_insertion()


def split_edges(m: topomesh.Mesh, faces: list[int]) -> set[tuple[int, int]]:
    sizes, idx = m.face_sizes, m.face_indices
    off = np.r_[0, np.cumsum(sizes)]
    out = set()
    for f in faces:
        vs_ = idx[off[f] : off[f + 1]]
        for a, b in zip(vs_, np.roll(vs_, -1)):
            out.add((min(a, b), max(a, b)))
    return out
