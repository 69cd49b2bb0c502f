"""Issue 19: the output-time Menger sponge and the allocator's block cache.

The sponge is compared cell by cell with an independent NumPy voxel-boundary
construction (the same faces, found by comparing every cell with its six
neighbours), so a wrong face, vertex or orientation shows up here.
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

import topomesh


def voxel_faces(level: int) -> set[tuple[tuple[int, ...], ...]]:
    """Every boundary square of the level-`level` sponge as its cycle of grid points
    (outward, counter-clockwise), from a plain voxel scan."""
    n = 3**level
    t = np.arange(n)
    ones = np.zeros(n, np.int64)
    for k in range(level):
        ones |= ((t // 3**k) % 3 == 1).astype(np.int64) << k
    a, b, c = ones[:, None, None], ones[None, :, None], ones[None, None, :]
    kept = np.pad(((a & b) | (b & c) | (a & c)) == 0, 1)
    out = set()
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        eu, ev = np.eye(3, dtype=int)[u], np.eye(3, dtype=int)[v]
        for sign in (-1, 1):
            shift = np.roll(kept, -sign, axis=axis)
            for cell in np.argwhere(kept & ~shift):
                p = cell - 1
                if sign == 1:
                    p = p + np.eye(3, dtype=int)[axis]
                    cyc = [p, p + eu, p + eu + ev, p + ev]
                else:
                    cyc = [p, p + ev, p + eu + ev, p + eu]
                out.add(tuple(tuple(int(x) for x in q) for q in cyc))
    return out


@pytest.mark.parametrize("level", [0, 1, 2, 3])
def test_sponge_faces_are_the_voxel_boundary(level):
    m = topomesh.menger_sponge(level)
    m.validate()
    n = 3**level
    g = np.rint((m.vertices + 1.0) * n / 2).astype(int)
    np.testing.assert_allclose(g * 2.0 / n - 1.0, m.vertices, atol=0)
    faces = m.face_indices.reshape(-1, 4)
    got = {tuple(tuple(int(x) for x in g[i]) for i in f) for f in faces}
    assert len(got) == m.n_faces == 2 * 20**level + 4 * 8**level
    assert got == voxel_faces(level)
    assert len(np.unique(g, axis=0)) == m.n_vertices


def test_sponge_is_deterministic_and_fresh():
    a, b = topomesh.menger_sponge(3), topomesh.menger_sponge(3)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    np.testing.assert_array_equal(a.edges, b.edges)
    np.testing.assert_array_equal(a.face_indices, b.face_indices)


def test_block_cache_off_by_default_and_bounded():
    limit, held = topomesh.block_cache()
    old = topomesh.set_block_cache(64 << 20)
    try:
        assert topomesh.block_cache()[0] == 64 << 20
        topomesh.cube().catmull_clark(6)  # frees large temporaries
        assert topomesh.block_cache()[1] <= 64 << 20
        assert topomesh.set_block_cache(0) == 64 << 20
        assert topomesh.block_cache() == (0, 0)
    finally:
        topomesh.set_block_cache(old)
    assert limit == old
    with pytest.raises(topomesh.MeshError, match=r"set_block_cache: nbytes = -1 must be in"):
        topomesh.set_block_cache(-1)
    with pytest.raises(topomesh.MeshError, match=r"set_block_cache: nbytes"):
        topomesh.set_block_cache(2**31)


def _child(env: dict[str, str], code: str) -> subprocess.CompletedProcess[str]:
    full = {**os.environ, **env}
    return subprocess.run([sys.executable, "-c", code], env=full, capture_output=True, text=True, timeout=120)


def test_block_cache_default_and_environment():
    code = "import topomesh; print(*topomesh.block_cache())"
    env = {k: v for k, v in os.environ.items() if k != "TOPOMESH_BLOCK_CACHE"}
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert r.stdout.split() == ["0", "0"], r.stderr
    r = _child({"TOPOMESH_BLOCK_CACHE": "32M"}, code)
    assert r.stdout.split()[0] == str(32 << 20), r.stderr
    r = _child({"TOPOMESH_BLOCK_CACHE": "lots"}, code)
    assert r.returncode != 0 and "TOPOMESH_BLOCK_CACHE" in r.stderr


def test_huge_page_advice_is_opt_in():
    # off by default (first calls stalled 2-5x with it, benches/README.md); the
    # environment turns it on or off, and a value it cannot read is an error naming it
    code = "import topomesh; print(*topomesh._core._huge_page_advice())"
    clean = {k: v for k, v in os.environ.items() if not k.startswith("TOPOMESH_HUGE")}

    def run(**env):
        return subprocess.run([sys.executable, "-c", code], env={**clean, **env}, capture_output=True, text=True, timeout=120)

    r = run()
    assert r.stdout.split() == ["False", str(64 << 20)], r.stderr
    for value, on in [("1", "True"), ("on", "True"), ("YES", "True"), ("0", "False"), ("off", "False"), ("", "False")]:
        r = run(TOPOMESH_HUGE_PAGES=value)
        assert r.stdout.split()[0] == on, (value, r.stderr)
    r = run(TOPOMESH_HUGE_PAGES_MAX="1G")
    assert r.stdout.split()[1] == str(1 << 30), r.stderr
    for var, bad in [("TOPOMESH_HUGE_PAGES", "maybe"), ("TOPOMESH_HUGE_PAGES_MAX", "lots")]:
        r = run(**{var: bad})
        assert r.returncode != 0 and f'{var} = "{bad}"' in r.stderr, r.stderr


def test_populate_is_on_by_default_and_changes_no_result():
    # output pages mapped in one call before the fill (src/mesh/populate.rs, on
    # Linux 5.14+); TOPOMESH_POPULATE=0 turns it off, a value it cannot read is an
    # error naming it, and the meshes are the same either way
    code = (
        "import hashlib, topomesh\n"
        "m = topomesh.icosahedron().loop(4)\n"
        "outs = [m.loop(2), m.midpoint(2), topomesh.torus(60, 40).catmull_clark(2), m.doo_sabin(1), m.honeycomb(1)]\n"
        "h = hashlib.sha256()\n"
        "for o in outs:\n"
        "    h.update(o.vertices.tobytes()); h.update(o.face_indices.tobytes()); h.update(o.face_sizes.tobytes())\n"
        "print(topomesh._core._populate(), h.hexdigest())"
    )
    clean = {k: v for k, v in os.environ.items() if k != "TOPOMESH_POPULATE"}

    def run(**env):
        return subprocess.run([sys.executable, "-c", code], env={**clean, **env}, capture_output=True, text=True, timeout=300)

    default, off = run(), run(TOPOMESH_POPULATE="0")
    assert default.returncode == 0 and off.returncode == 0, default.stderr + off.stderr
    assert default.stdout.split()[0] == ("True" if sys.platform == "linux" else "False"), default.stdout
    assert off.stdout.split()[0] == "False", off.stdout
    assert default.stdout.split()[1] == off.stdout.split()[1]
    r = run(TOPOMESH_POPULATE="maybe")
    assert r.returncode != 0 and 'TOPOMESH_POPULATE = "maybe"' in r.stderr, r.stderr


def test_zeroed_blocks_read_zero_after_dirty_ones():
    # large zeroed blocks drop their absent pages instead of writing them
    # (src/python/alloc.rs, zero_block); after a dirty block of the same size
    # was freed, fully written (resident) or only its first MiB (mostly
    # absent), and at sizes that are not whole pages, every byte reads zero;
    # with TOPOMESH_ZERO_DROP=0 too, and a value it cannot read is an error
    sizes = [1 << 20, (1 << 20) + 123, 5 << 20, (17 << 20) + 4095, 40 << 20]
    code = f"import topomesh; print(topomesh._core._zeroed_blocks_are_zero({sizes}))"
    clean = {k: v for k, v in os.environ.items() if k != "TOPOMESH_ZERO_DROP"}

    def run(**env):
        return subprocess.run([sys.executable, "-c", code], env={**clean, **env}, capture_output=True, text=True, timeout=120)

    for env in [{}, {"TOPOMESH_ZERO_DROP": "0"}]:
        r = run(**env)
        assert r.stdout.split() == ["True"], (env, r.stderr)
    r = run(TOPOMESH_ZERO_DROP="maybe")
    assert r.returncode != 0 and 'TOPOMESH_ZERO_DROP = "maybe"' in r.stderr, r.stderr
    with pytest.raises(topomesh.MeshError, match="above 1 GiB"):
        topomesh._core._zeroed_blocks_are_zero([2 << 30])


def test_results_same_with_and_without_cache():
    old = topomesh.set_block_cache(256 << 20)
    try:
        warm = [topomesh.torus(40, 30).loop(2).vertices for _ in range(2)]
    finally:
        topomesh.set_block_cache(old)
    cold = topomesh.torus(40, 30).loop(2).vertices
    np.testing.assert_array_equal(warm[0], cold)
    np.testing.assert_array_equal(warm[1], cold)


@pytest.mark.parametrize(
    "make",
    [lambda: topomesh.icosahedron().loop(2), lambda: topomesh.tetrahedron(), lambda: topomesh.torus(12, 8).loop(1),
     lambda: topomesh.cube(), lambda: topomesh.tetrahedron().sierpinski(2)],
    ids=["loop-sphere", "tetrahedron", "loop-torus", "quads", "self-loops"],
)
def test_triangles_fast_path_matches_triangulate(make):
    m = make()
    _, tris, faces = m.triangulate()
    t, f = m.triangles(return_faces=True)
    assert t.dtype == np.int64 and t.shape == tris.shape
    np.testing.assert_array_equal(t, tris)
    np.testing.assert_array_equal(f, faces)
    np.testing.assert_array_equal(m.triangles(), tris)


def test_triangles_fast_path_is_the_faces():
    m = topomesh.icosahedron().loop(1)
    np.testing.assert_array_equal(m.triangles(), m.face_indices.reshape(-1, 3))
    # an open triangle mesh (hole faces) still leaves the holes out
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.2]], float)
    o = topomesh.Mesh.from_polygons(v, [[0, 1, 2], [1, 3, 2]])
    np.testing.assert_array_equal(o.triangles(), [[0, 1, 2], [1, 3, 2]])


def _exports(m):
    return m.vertices.copy(), m.face_indices.copy(), m.edges.copy()


def test_block_cache_reuse_gives_the_same_meshes():
    # With the cache on, a freed block serves a later request of half its size
    # or more (src/python/alloc.rs); what comes back must be what a fresh
    # block gives, call after call, at sizes that do and do not fit.
    calls = [
        lambda: topomesh.cube().catmull_clark(6),
        lambda: topomesh.torus(200, 100).loop(2),
        lambda: topomesh.menger_sponge(3),
        lambda: topomesh.cube().catmull_clark(5),  # smaller than the blocks cached above
        lambda: topomesh.torus(200, 100).loop(1),
    ]
    want = [_exports(c()) for c in calls]
    old = topomesh.set_block_cache(256 << 20)
    try:
        for _ in range(2):
            for c, w in zip(calls, want):
                got = _exports(c())
                for a, b in zip(got, w):
                    np.testing.assert_array_equal(a, b)
        assert topomesh.block_cache()[1] > 0  # the cache took blocks back
    finally:
        topomesh.set_block_cache(old)

