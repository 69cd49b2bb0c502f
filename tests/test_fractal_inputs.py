"""The example inputs of topomesh.examples (one per vertex class of the
Sierpinski paper) and what the Sierpinski scheme does with them."""

from __future__ import annotations

import math

import numpy as np
import pytest

import topomesh
from topomesh import examples
from tests.harness import assert_agrees_with_peers

#: builder -> the class of its vertex 0, as the docstrings claim
CLAIMS = {
    "star_prism": "star",
    "dented_cube": "concave",
    "planar_vertex_box": "planar",
    "monkey_saddle": "saddle",
}
BUILDERS = {name: getattr(examples, name) for name in CLAIMS}
TOL = 1e-9


def corners_at(m: topomesh.Mesh, v: int) -> list[list[int]]:
    """Each face corner at ``v`` as the face's vertex cycle rotated to start at ``v``."""
    sizes, idx = m.face_sizes, m.face_indices
    off = np.concatenate([[0], np.cumsum(sizes)])
    out = []
    for f in range(len(sizes)):
        cyc = list(idx[off[f] : off[f + 1]])
        out += [cyc[i:] + cyc[:i] for i, w in enumerate(cyc) if w == v]
    return out


def link(m: topomesh.Mesh, v: int) -> list[int]:
    """The neighbours of ``v`` along its edges, in order around it (the base of
    the paper's pyramid): the faces at ``v`` chained, a face's last vertex
    before ``v`` being the next face's first after it."""
    corners = {c[1]: c for c in corners_at(m, v)}
    start = next(iter(corners))
    ring, cur = [], start
    for _ in range(len(corners)):
        ring.append(cur)
        cur = corners[cur][-1]
    assert cur == start and len(corners) == len(corners_at(m, v)), "vertex is not a disk"
    return ring


def angle_deficit(m: topomesh.Mesh, v: int) -> float:
    """2π minus the face angles at ``v``; a reflex corner of a non-convex face
    (turning against the face's Newell normal) counts its angle above π."""
    p = m.vertices
    total = 0.0
    for c in corners_at(m, v):
        q = p[c]
        nf = np.cross(q, np.roll(q, -1, axis=0)).sum(axis=0)
        a, b = q[1] - q[0], q[-1] - q[0]
        total += math.atan2(np.cross(a, b) @ nf / np.linalg.norm(nf), a @ b) % (2 * math.pi)
    return 2 * math.pi - total


def vertex_normal(m: topomesh.Mesh, v: int) -> np.ndarray:
    """Sum of the (Newell) normals of the faces at ``v``, normalized."""
    p = m.vertices
    n = np.zeros(3)
    for c in corners_at(m, v):
        q = p[c]
        n += np.cross(q, np.roll(q, -1, axis=0)).sum(axis=0)
    return n / np.linalg.norm(n)


def classify(m: topomesh.Mesh, v: int) -> str:
    """The paper's vertex class, from the angle deficit δ, the neighbours'
    heights along the vertex normal and the convexity of the projected link
    (see topomesh.examples). Zero-curvature vertices that are not planar are
    'crease'; anything else is 'mixed'."""
    p = m.vertices
    n = vertex_normal(m, v)
    ring = link(m, v)
    h = (p[ring] - p[v]) @ n
    delta = angle_deficit(m, v)
    scale = max(np.abs(p[ring] - p[v]).max(), 1.0)
    if abs(delta) < TOL:
        return "planar" if np.all(np.abs(h) < TOL * scale) else "crease"
    if delta > 0 and np.all(h > TOL):
        return "concave"
    if delta > 0 and np.all(h < -TOL):
        # project the link on the plane normal to n, walk it: convex iff every turn has one sign
        e1 = np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        q = np.column_stack([(p[ring] - p[v]) @ e1, (p[ring] - p[v]) @ e2])
        d = np.roll(q, -1, axis=0) - q
        turns = d[:, 0] * np.roll(d, -1, axis=0)[:, 1] - d[:, 1] * np.roll(d, -1, axis=0)[:, 0]
        return "convex" if np.all(turns > -TOL) or np.all(turns < TOL) else "star"
    signs = np.sign(h[np.abs(h) > TOL])
    changes = int(np.sum(signs != np.roll(signs, 1)))
    return "saddle" if delta < 0 and changes >= 4 else "mixed"


# --- the inputs ------------------------------------------------------------


@pytest.mark.parametrize("name", list(CLAIMS))
def test_builder_is_a_closed_genus0_mesh_the_peers_accept(name):
    m = BUILDERS[name]()
    m.validate()
    assert m.n_holes == 0 and m.n_self_loops == 0
    assert m.genus == 0 and m.n_components == 1
    assert m.volume > 0
    assert_agrees_with_peers(m, expect_genus=0)


@pytest.mark.parametrize("name", list(CLAIMS))
def test_vertex_zero_has_the_claimed_class(name):
    assert classify(BUILDERS[name](), 0) == CLAIMS[name]


@pytest.mark.parametrize("name", list(CLAIMS))
def test_angle_deficits_sum_to_4pi(name):
    """Gauss-Bonnet for genus 0: checks the deficits, reflex face corners included."""
    m = BUILDERS[name]()
    assert sum(angle_deficit(m, v) for v in range(m.n_vertices)) == pytest.approx(4 * math.pi)


def test_classifier_on_known_vertices():
    cube = topomesh.cube()
    assert {classify(cube, v) for v in range(8)} == {"convex"}
    octa = topomesh.octahedron()
    assert {classify(octa, v) for v in range(6)} == {"convex"}


def test_vertex_class_census():
    """Every vertex of each input classified: the named class is where the docstrings say."""

    def census(m):
        out: dict[str, int] = {}
        for v in range(m.n_vertices):
            c = classify(m, v)
            out[c] = out.get(c, 0) + 1
        return out

    # apex: star; 10 tips: convex; 5 top reflex corners: saddles; 5 bottom
    # reflex corners: three-valent with δ < 0 (cannot alternate four times)
    assert census(examples.star_prism()) == {"star": 1, "convex": 10, "saddle": 5, "mixed": 5}
    # the dent pulls the top corners' links in: star vertices (the paper's Fig. 9 pairs the two)
    assert census(examples.dented_cube()) == {"concave": 1, "star": 4, "convex": 4}
    # 6 face centres planar, 12 edge midpoints on a crease, 8 corners convex
    assert census(examples.planar_vertex_box()) == {"planar": 6, "crease": 12, "convex": 8}
    assert classify(examples.planar_vertex_box(n=4), 0) == "planar"
    assert census(examples.planar_vertex_box(n=4))["planar"] == 6 * 9
    assert census(examples.monkey_saddle())["saddle"] == 1


def test_star_prism_has_a_non_convex_face():
    m = examples.star_prism(points=5)
    assert m.face_size_histogram == {3: 10, 4: 10, 10: 1}
    assert (m.n_vertices, m.n_edges, m.n_faces) == (21, 40, 21)
    assert m.face_sizes[-1] == 10
    # a non-convex polygon has turns of both signs
    q = m.vertices[m.face_indices[-10:]][:, :2]
    d = np.roll(q, -1, axis=0) - q
    turns = d[:, 0] * np.roll(d, -1, axis=0)[:, 1] - d[:, 1] * np.roll(d, -1, axis=0)[:, 0]
    assert (turns > 0).sum() == 5 and (turns < 0).sum() == 5


def test_builders_reject_bad_parameters():
    with pytest.raises(ValueError):
        examples.star_prism(points=2)
    with pytest.raises(ValueError):
        examples.dented_cube(depth=2.5)
    with pytest.raises(ValueError):
        examples.planar_vertex_box(n=1)
    with pytest.raises(ValueError):
        examples.monkey_saddle(sides=5)


# --- Sierpinski on them ----------------------------------------------------


@pytest.mark.parametrize("name", list(CLAIMS))
@pytest.mark.parametrize("k", [1, 2, 3])
def test_sierpinski_counts_follow_the_documented_formula(name, k):
    """src/schemes/sierpinski.rs: with no self-loops (N = E, K = V, F₀ = 0,
    D = 0) and s = (4ᵏ − 1)/3, Vₖ = V + E·s, Eₖ = E + 4E·s, Fₖ = V + 2E·s,
    Lₖ = E·s, χₖ = 2V − E − E·s."""
    m = BUILDERS[name]()
    V, E = m.n_vertices, m.n_edges
    s = (4**k - 1) // 3
    out = m.sierpinski(k)
    out.validate()
    chi = 2 * V - E - E * s
    assert (out.n_vertices, out.n_edges, out.n_faces, out.n_self_loops) == (V + E * s, E + 4 * E * s, V + 2 * E * s, E * s)
    assert out.euler_characteristic == chi
    assert out.genus == 1 - chi // 2 and out.n_components == 1
    # iterating one step at a time gives the same mesh
    step = m
    for _ in range(k):
        step = step.sierpinski()
    assert step == out


def _pyramid_volume(m: topomesh.Mesh, v: int) -> float:
    """Signed volume of the pyramid at old vertex ``v`` of a Sierpinski
    output: its corner triangles closed by the plane base through the
    midpoints (apex-to-midpoint cone seen from the base centroid)."""
    p = m.vertices
    tris = corners_at(m, v)
    assert all(len(set(t)) == 3 for t in tris), "corner faces at an old vertex are triangles"
    c = p[sorted({w for t in tris for w in t[1:]})].mean(axis=0)
    return sum(float(np.dot(p[a] - c, np.cross(p[b] - c, p[d] - c))) for a, b, d in (t[:3] for t in tris)) / 6


def test_sierpinski_pyramids_by_vertex_class():
    """Section 5 of the paper: a convex or star vertex gives a pyramid of
    positive volume, a concave vertex an inverted one (negative volume), a
    planar vertex a flattened one (zero volume)."""
    cube = topomesh.cube()
    assert _pyramid_volume(cube.sierpinski(1), 0) > 0
    star = examples.star_prism().sierpinski(1)
    assert np.allclose(star.vertices[:21], examples.star_prism().vertices)  # old vertices keep their ids
    assert _pyramid_volume(star, 0) > 0
    assert _pyramid_volume(examples.dented_cube().sierpinski(1), 0) < 0
    flat = examples.planar_vertex_box().sierpinski(1)
    assert abs(_pyramid_volume(flat, 0)) < 1e-12
    assert np.allclose(flat.vertices[[w for t in corners_at(flat, 0) for w in t], 2], 0.5)


def test_star_vertex_gives_a_star_shaped_back_face():
    """The apex's back face runs through the midpoints of its 10 edges, one
    self-loop at each (20 corners), and is non-convex (a star)."""
    s = examples.star_prism().sierpinski(1)
    sizes = s.face_sizes
    off = np.concatenate([[0], np.cumsum(sizes)])
    (big,) = np.nonzero(sizes == 20)[0][:1]
    cyc = s.face_indices[off[big] : off[big + 1]]
    pts = [v for i, v in enumerate(cyc) if v != cyc[i - 1]]  # drop the self-loop repeats
    q = s.vertices[pts][:, :2]
    assert len(q) == 10 and np.allclose(s.vertices[pts][:, 2], s.vertices[pts][0, 2])
    d = np.roll(q, -1, axis=0) - q
    turns = d[:, 0] * np.roll(d, -1, axis=0)[:, 1] - d[:, 1] * np.roll(d, -1, axis=0)[:, 0]
    assert (turns > 0).any() and (turns < 0).any()



@pytest.mark.parametrize("name", list(CLAIMS))
@pytest.mark.parametrize("k", [1, 2, 3])
def test_sierpinski_doo_sabin_agrees_with_peers(name, k):
    s = BUILDERS[name]().sierpinski(k)
    smooth = s.doo_sabin(2)
    assert smooth.genus == s.genus
    assert smooth.n_self_loops == 0
    assert smooth.n_components == 1
    assert_agrees_with_peers(smooth, planar=False)
