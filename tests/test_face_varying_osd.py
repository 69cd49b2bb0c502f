"""OpenSubdiv's face-varying choices ``corners_plus1`` / ``corners_plus2`` (FVAR_LINEAR_CORNERS_PLUS1 /
PLUS2; Blender's UV Smooth "Keep Corners, Junctions" / "… and Concave") beside the other four, checked
against OpenSubdiv itself through Blender's bpy (tests/osd; skipped with the reason when absent; set
``TOPOMESH_BPY_PYTHON`` to an interpreter that has bpy, e.g. another worktree's ``.venv-bpy``).

The fixtures make the modes differ: a disk whose centre is a junction of three UV islands of two faces
each, with a seam that ends inside (a dart), and a disk whose centre joins a one-face island to a
five-face one (concave). The cross-unfolded cube of tests/osd is compared too.
"""

from __future__ import annotations

import numpy as np
import pytest

import topomesh as tm
from tests import open_meshes
from tests.osd import assert_same_mesh, available, refine_many, request
from tests.osd import fixtures as F

MODES = ["all", "corners_only", "corners_plus1", "corners_plus2", "boundaries", "none"]
OURS = {"none": "smooth"}  # Blender/OpenSubdiv's FVAR_LINEAR_NONE is topomesh's "smooth"
LEVELS = (1, 2)
N = 6  # disk sectors: triangle 0-inner(i)-inner(i+1) and the quad outside it


def _disk() -> tuple[np.ndarray, list[list[int]]]:
    v, f = open_meshes.disk(N)
    return v, f


def _sector(face: list[int]) -> int:
    """The sector of a disk face: the smaller inner-ring index it uses (mod N), cyclically."""
    inner = sorted({(i - 1) % N for i in face if 1 <= i <= N})
    a, b = inner
    return a if (b - a) == 1 else b


def _uvs(v: np.ndarray, faces: list[list[int]], island, shift) -> np.ndarray:
    """Per-corner UVs: xy + a per-island offset, + ``shift(face, vertex)``."""
    out = []
    for f in faces:
        k = island(_sector(f))
        for i in f:
            out.append(v[i, :2] + np.array([2.5 * k, 0.0]) + shift(f, i))
    return np.array(out)


def junction_disk() -> tuple[np.ndarray, list[list[int]], np.ndarray]:
    """Three islands (sectors {0,1}, {2,3}, {4,5}) meet at the centre, each with two faces there;
    sector 1's quad is cut from sector 0's along the radial edge to outer(1) only: inner(1) is a dart."""
    v, faces = _disk()
    outer1 = 1 + N + 1

    def shift(f, i):
        return np.array([0.05, 0.02]) if (_sector(f) == 1 and i == outer1 and len(f) == 4) else np.zeros(2)

    return v, faces, _uvs(v, faces, lambda s: s // 2, shift)


def concave_disk() -> tuple[np.ndarray, list[list[int]], np.ndarray]:
    """Sector 0 is an island of its own: the centre has two values, of one face and of five."""
    v, faces = _disk()
    return v, faces, _uvs(v, faces, lambda s: 0 if s == 0 else 1, lambda f, i: np.zeros(2))


def cube() -> tuple[np.ndarray, list[list[int]], np.ndarray]:
    fx = F.uv_cube()
    return fx.vertices, fx.faces, fx.options["uvs"]


FIXTURES = {"junction_disk": junction_disk, "concave_disk": concave_disk, "uv_cube": cube}


def ours(name: str, level: int, mode: str, scheme: str = "catmull_clark") -> tm.Mesh:
    v, f, uv = FIXTURES[name]()
    m = tm.Mesh.from_polygons(v, f).with_attributes(corner={"uv": uv})
    return getattr(m, scheme)(level, corner_interpolation=OURS.get(mode, mode))


@pytest.fixture(scope="module")
def ref():
    reason = available()
    if reason is not None:
        pytest.skip(reason)
    keys = [(n, lv, mo) for n in FIXTURES for lv in LEVELS for mo in MODES]
    reqs = []
    for n, lv, mo in keys:
        v, f, uv = FIXTURES[n]()
        reqs.append(request(v, f, lv, uvs=uv, uv_interpolation=mo))
    return dict(zip(keys, refine_many(reqs)))


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("name", list(FIXTURES))
def test_face_varying_modes_equal_opensubdiv(ref, name, level, mode):
    out = ours(name, level, mode)
    assert_same_mesh(out.vertices, (out.face_sizes, out.face_indices), ref[(name, level, mode)], out.corner_attributes["uv"])


@pytest.mark.parametrize("name", ["junction_disk", "concave_disk"])
def test_the_fixtures_tell_the_modes_apart(ref, name):
    """The comparison above is not vacuous: the reference's UVs differ between the modes this
    fixture is for (plus1 vs corners_only at the junction, plus2 vs plus1 at the concave corner
    and the dart)."""
    r = {mo: ref[(name, 1, mo)].uvs for mo in MODES}
    assert not np.allclose(r["corners_plus2"], r["corners_plus1"], atol=1e-4)
    if name == "junction_disk":
        assert not np.allclose(r["corners_plus1"], r["corners_only"], atol=1e-4)


def _centre_corner_uvs(out: tm.Mesh, v0: np.ndarray) -> np.ndarray:
    """UVs of the output corners at the (unmoved or moved) centre vertex point."""
    c = np.argmin(np.linalg.norm(out.vertices - v0, axis=1))
    return out.corner_attributes["uv"][out.face_indices == c]


@pytest.mark.parametrize("scheme", ["catmull_clark", "loop"])
def test_plus_rules_pin_junctions_and_concave_corners(scheme):
    """The rules themselves (no reference needed, Loop included): at the junction centre the
    values stay put with corners_plus1/2 and move with corners_only; at the concave centre
    corners_plus2 keeps both values, corners_plus1 only the one-face island's."""
    v, f, uv = junction_disk()
    start = {tuple(np.round(u, 12)) for u in uv[np.concatenate(f) == 0]}
    assert len(start) == 3
    for mode, pinned in (("corners_only", False), ("corners_plus1", True), ("corners_plus2", True)):
        got = {tuple(np.round(u, 12)) for u in _centre_corner_uvs(ours("junction_disk", 1, mode, scheme), v[0])}
        assert (got == start) == pinned, mode
    v, f, uv = concave_disk()
    start = {tuple(np.round(u, 12)) for u in uv[np.concatenate(f) == 0]}
    assert len(start) == 2
    kept = {m: len(start & {tuple(np.round(u, 12)) for u in _centre_corner_uvs(ours("concave_disk", 1, m, scheme), v[0])})
            for m in ("corners_only", "corners_plus1", "corners_plus2")}
    assert kept == {"corners_only": 1, "corners_plus1": 1, "corners_plus2": 2}


def test_unknown_mode_names_the_choices():
    v, f, uv = cube()
    m = tm.Mesh.from_polygons(v, f).with_attributes(corner={"uv": uv})
    with pytest.raises(tm.MeshError, match='"corners_plus1", "corners_plus2"'):
        m.catmull_clark(corner_interpolation="corners_plus3")
