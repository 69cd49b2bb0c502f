"""Data through the Conway operators, TopMod's remeshing schemes and the object tools
(issue 15, item 4: attributes must never vanish unannounced).

These operators rebuild the faces and edges: a mesh with creases or attributes gets a
``GeometryWarning`` that names every dropped array. The Conway operators and TopMod's
schemes built through the keyed builder carry face attributes to the child faces and drop
the rest. The operators that only move positions (``canonicalize``, ``planarize``,
``spherize``) keep all of it, and ``reflect`` (same vertices, same faces in the same order)
keeps the vertex and face attributes.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import topomesh as tm


def with_all(m: tm.Mesh) -> tm.Mesh:
    nf, nc = len(m.face_sizes), len(m.face_indices)
    return m.with_creases({tuple(m.edges[0]): 2.0}).with_attributes(
        vertex={"rgb": np.linspace(0, 1, 3 * m.n_vertices).reshape(-1, 3)},
        face={"material": np.arange(nf) % 3},
        corner={"uv": np.c_[np.arange(nc) % 4, np.arange(nc) // 4].astype(float)},
    )


DROPPING = {
    "subdivide_all_edges": lambda m: m.subdivide_all_edges(),
    "wireframe": lambda m: m.wireframe(0.1),
    "cut_faces": lambda m: m.cut_faces([0]),
}

# the catalog built through the keyed builder (and root3, dual_loop, doo_sabin_bc through
# their middle scheme's origins): face attributes are inherited by the child faces
# (tests/test_catalog_face_data.py), the rest is named and dropped
INHERITING = {
    "root3": lambda m: m.root3(),
    "dual_loop": lambda m: m.dual_loop(),
    "doo_sabin_bc": lambda m: m.doo_sabin_bc(),
    "truncate": lambda m: m.truncate(),
    "kis": lambda m: m.kis(),
    "ambo": lambda m: m.ambo(),
    "join": lambda m: m.join(),
    "gyro": lambda m: m.gyro(),
    "conway": lambda m: m.conway("tk"),
    "stellate": lambda m: m.stellate(),
    "corner_cutting": lambda m: m.corner_cutting(),
    "extrude": lambda m: m.extrude([0]),
}


@pytest.mark.parametrize("name", sorted(DROPPING))
def test_rebuilding_operators_name_what_they_drop(name: str) -> None:
    op = DROPPING[name]
    c = tm.cube()
    plain = op(c)  # no data: no warning (filterwarnings = error)
    with pytest.warns(tm.GeometryWarning) as rec:
        out = op(with_all(c))
    msg = str(rec[0].message)
    for part in ("creases", 'vertex attributes ["rgb"]', 'face attributes ["material"]', 'corner attributes ["uv"]'):
        assert part in msg, (part, msg)
    assert msg.startswith(name)
    assert out == plain and not out.vertex_attributes and not out.face_attributes and not out.corner_attributes
    # only what is there is named
    with pytest.warns(tm.GeometryWarning, match=r'the input\'s face attributes \["material"\] \(') as rec:
        op(c.with_attributes(face={"material": np.arange(6)}))
    named = str(rec[0].message).split(" (this operator")[0]
    assert "vertex" not in named and "creases" not in named


@pytest.mark.parametrize("name", sorted(INHERITING))
def test_catalog_names_what_it_drops_and_keeps_face_data(name: str) -> None:
    op = INHERITING[name]
    c = tm.cube()
    plain = op(c)
    with pytest.warns(tm.GeometryWarning) as rec:
        out = op(with_all(c))
    msg = str(rec[0].message)
    assert msg.startswith(name)
    for part in ("creases", 'vertex attributes ["rgb"]', 'corner attributes ["uv"]'):
        assert part in msg, (part, msg)
    assert "face attributes" not in msg.split(" (this operator")[0]
    assert out == plain and not out.vertex_attributes and not out.corner_attributes
    assert set(out.face_attributes) == {"material"} and len(out.face_attributes["material"]) == len(out.face_sizes)
    # face data alone: nothing dropped, no warning (filterwarnings = error)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        op(c.with_attributes(face={"material": np.arange(6)}))


@pytest.mark.parametrize("name", ["canonicalize", "planarize", "spherize"])
def test_position_only_tools_keep_every_array(name: str) -> None:
    d = with_all(tm.cube())
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = getattr(d, name)()
    out = got[0] if isinstance(got, tuple) else got
    assert out.n_vertices == d.n_vertices and (out.face_indices == d.face_indices).all()
    for kind in ("vertex_attributes", "face_attributes", "corner_attributes"):
        a, b = getattr(d, kind), getattr(out, kind)
        assert a.keys() == b.keys()
        for k in a:
            np.testing.assert_array_equal(a[k], b[k])
    np.testing.assert_array_equal(out.edge_sharpness, d.edge_sharpness)


def test_reflect_keeps_vertex_and_face_attributes() -> None:
    c = tm.cube()
    vf = c.with_attributes(vertex={"rgb": np.arange(24.0).reshape(8, 3)}, face={"material": np.arange(6) * 10})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = vf.reflect()
    np.testing.assert_array_equal(r.vertex_attributes["rgb"], vf.vertex_attributes["rgb"])
    np.testing.assert_array_equal(r.face_attributes["material"], np.arange(6) * 10)
    np.testing.assert_allclose(r.vertices, -c.vertices)
    # the corners and edges are renumbered: those are named and dropped
    with pytest.warns(tm.GeometryWarning, match=r'reflect: .*creases, corner attributes \["uv"\]') as rec:
        r2 = with_all(c).reflect()
    assert "vertex attributes" not in str(rec[0].message).split(" (this operator")[0]
    assert set(r2.vertex_attributes) == {"rgb"} and set(r2.face_attributes) == {"material"} and not r2.corner_attributes
