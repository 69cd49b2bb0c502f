"""The fuzz target of issue 14: seeded random construction input, operator
sequences and scheme steps, with every output checked.

Each case builds a mesh (a primitive, a torus, a tunnelled slab, or random
polygon input that may be garbage), applies up to three random operators
and at most one scheme level, and asserts for every mesh it gets:

* nothing but ``MeshError`` is raised (no panic, no other exception type),
* ``validate()`` holds,
* the mesh round-trips: ``from_flat`` with its ``corner_twins`` and
  ``pickle`` give an equal mesh,
* on simple meshes (no self-loop, multi-edge, face with fewer than three
  distinct corners, point-sphere or hole) the triangulation uses every
  triangle edge exactly twice, and trimesh agrees with topomesh on
  watertightness, winding and χ;
* on simple meshes that are also *realized* (no zero-area triangle, no two
  triangles on one vertex triple, no self-intersection by
  ``Mesh.self_intersections``), manifold3d accepts the triangles with the
  same genus. manifold3d simplifies the topology of degenerate and
  self-intersecting input on construction (the operators here make plenty:
  an InsertEdge handle has no thickness), so it is only a peer on realized
  geometry.

The peers are called once per batch of cases on the disjoint union of the
batch's triangulations (χ and genus add up over disjoint pieces); a batch
that disagrees is checked case by case to name the culprit. Aborts are
caught by the test running this module in a subprocess.

Run by hand: ``python -m tests.fuzz --cases 1000000 --seed 1``.
"""

from __future__ import annotations

import argparse
import pickle
import sys
import time
import traceback
import warnings
from dataclasses import dataclass, field

import numpy as np

import topomesh
from topomesh import Mesh, MeshError

SCHEMES = ("catmull_clark", "doo_sabin", "loop", "sqrt3", "simplest", "midpoint", "dual", "honeycomb",
           "vertex_truncation", "sierpinski")
OPS = ("delete_edge", "insert_edge", "connect_edges", "create_pipe", "subdivide_edge", "collapse_edge",
       "create_vertex", "delete_edge_with_cleanup")


@dataclass
class Stats:
    cases: int = 0
    meshes: int = 0
    rejected: int = 0  # MeshError on construction or a precondition
    simple: int = 0
    realized: int = 0
    peer_batches: int = 0
    failures: list = field(default_factory=list)


def _base(rng: np.random.Generator) -> Mesh:
    k = int(rng.integers(0, 9))
    if k < 5:
        m = (topomesh.tetrahedron, topomesh.cube, topomesh.octahedron, topomesh.dodecahedron, topomesh.icosahedron)[k]()
        # jitter keeps faces non-planar and non-convex now and then
        return m.with_vertices(m.vertices + rng.normal(0, 0.15, m.vertices.shape) * rng.integers(0, 2))
    if k == 5:
        return topomesh.torus(int(rng.integers(3, 7)), int(rng.integers(3, 6)))
    if k == 6:
        return topomesh.genus_surface(int(rng.integers(1, 3)))
    # random polygon input: mostly garbage, sometimes a valid mesh
    nv = int(rng.integers(1, 12))
    v = rng.normal(size=(nv, 3))
    if rng.random() < 0.05:
        v[int(rng.integers(nv))] = np.nan
    nf = int(rng.integers(1, 8))
    sizes = rng.integers(-1, 6, nf)
    idx = rng.integers(-1, nv + 1, max(int(sizes.clip(0).sum()), 0))
    return Mesh.from_flat(v, sizes, idx, close_boundaries=bool(rng.random() < 0.3),
                          allow_multi_edges=bool(rng.random() < 0.3))


def _op(rng: np.random.Generator, m: Mesh) -> Mesh:
    op = OPS[int(rng.integers(len(OPS)))]
    sizes = m.face_sizes
    nf = len(sizes)
    if op in ("delete_edge", "subdivide_edge", "collapse_edge", "delete_edge_with_cleanup"):
        if m.n_edges == 0:
            return m
        e = int(rng.integers(m.n_edges))
        r = getattr(m, op)(e)
        return r[0] if isinstance(r, tuple) else r
    if op == "create_vertex":
        return m.create_vertex(rng.normal(size=3).tolist())[0]
    if nf == 0:
        return m
    f1, f2 = int(rng.integers(nf)), int(rng.integers(nf))
    p1, p2 = int(rng.integers(sizes[f1])), int(rng.integers(sizes[f2]))
    r = getattr(m, op)(f1, p1, f2, p2)
    return r[0] if isinstance(r, tuple) else r


def is_simple(m: Mesh) -> bool:
    """No self-loop, multi-edge, point-sphere, hole, or face with fewer than
    three distinct corners: the meshes whose triangulation must be exact."""
    if m.n_self_loops or m.n_holes or m.n_faces == 0:
        return False
    e = np.sort(m.edges, axis=1)
    if len(np.unique(e, axis=0)) != len(e):
        return False
    sizes, idx = m.face_sizes, m.face_indices
    if sizes.min() < 3:
        return False
    starts = np.r_[0, np.cumsum(sizes)[:-1]]
    for s, n in zip(starts, sizes):
        if len(set(idx[s:s + n].tolist())) != n:
            return False
    return True


def check_triangulation(m: Mesh) -> tuple[np.ndarray, np.ndarray]:
    """Every edge of the triangle mesh used by exactly two triangles, once
    each way."""
    verts, tris, _ = m.triangulate()
    half = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    key = half[:, 0] * len(verts) + half[:, 1]
    assert len(np.unique(key)) == len(key), "a triangle edge is used twice in one direction"
    rev = half[:, 1] * len(verts) + half[:, 0]
    assert np.isin(rev, key).all(), "a triangle edge has one side only"
    return verts, tris


def check_mesh(m: Mesh) -> None:
    m.validate()
    back = Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices, twins=m.corner_twins)
    assert back == m, "from_flat(corner_twins) round trip differs"
    assert pickle.loads(pickle.dumps(m)) == m, "pickle round trip differs"


def is_realized(m: Mesh, verts: np.ndarray, tris: np.ndarray) -> bool:
    """No zero-area triangle, no repeated vertex triple, no self-intersection."""
    area = np.linalg.norm(np.cross(verts[tris[:, 1]] - verts[tris[:, 0]], verts[tris[:, 2]] - verts[tris[:, 0]]), axis=1)
    if area.min() <= 1e-12 * max(1.0, float(area.max())):
        return False
    if len(np.unique(np.sort(tris, axis=1), axis=0)) != len(tris):
        return False
    return len(m.self_intersections()) == 0


def _peers_agree(items: list[tuple[Mesh, np.ndarray, np.ndarray, bool]]) -> bool:
    import manifold3d as m3d
    import trimesh

    def union(sel):
        vs, ts, off = [], [], 0
        for _, v, t, _ in sel:
            vs.append(v)
            ts.append(t + off)
            off += len(v)
        return np.concatenate(vs), np.concatenate(ts), sum(m.euler_characteristic for m, _, _, _ in sel)

    v, t, chi = union(items)
    tm = trimesh.Trimesh(vertices=v, faces=t, process=False)
    if not (tm.is_watertight and tm.is_winding_consistent and int(tm.euler_number) == chi):
        return False
    real = [x for x in items if x[3]]
    if not real:
        return True
    v, t, chi = union(real)
    man = m3d.Manifold(m3d.Mesh(vert_properties=v.astype(np.float32), tri_verts=t.astype(np.uint32)))
    return man.status() == m3d.Error.NoError and int(man.genus()) == 1 - chi // 2


def run(cases: int, seed: int, batch: int = 256, log=None, start: int = 0) -> Stats:
    st = Stats()
    pending: list[tuple[int, Mesh, np.ndarray, np.ndarray, bool]] = []

    def flush():
        if not pending:
            return
        st.peer_batches += 1
        if not _peers_agree([(m, v, t, r) for _, m, v, t, r in pending]):
            for case, m, v, t, r in pending:
                if not _peers_agree([(m, v, t, r)]):
                    st.failures.append((case, f"peers disagree on {m!r}"))
        pending.clear()

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topomesh.GeometryWarning)
        for case in range(start, start + cases):
            st.cases += 1
            crng = np.random.default_rng([seed, case])
            try:
                m = _base(crng)
                chain = [m]
                for _ in range(int(crng.integers(0, 4))):
                    try:
                        m = _op(crng, m)
                    except MeshError:
                        st.rejected += 1
                    chain.append(m)
                if crng.random() < 0.3 and m.n_faces < 400:
                    try:
                        m = getattr(m, SCHEMES[int(crng.integers(len(SCHEMES)))])()
                    except MeshError:
                        st.rejected += 1
                    chain.append(m)
                for x in chain:
                    st.meshes += 1
                    check_mesh(x)
                if is_simple(m):
                    st.simple += 1
                    v, t = check_triangulation(m)
                    real = is_realized(m, v, t)
                    st.realized += real
                    pending.append((case, m, v, t, real))
                    if len(pending) >= batch:
                        flush()
            except MeshError:
                st.rejected += 1
            except (Exception, BaseException) as e:  # noqa: B036 - a PanicException is a BaseException
                if isinstance(e, KeyboardInterrupt):
                    raise
                st.failures.append((case, f"{type(e).__name__}: {e}\n{traceback.format_exc(limit=3)}"))
            if log and case % 10000 == 0 and case:
                print(f"{case} cases, {len(st.failures)} failures", file=log, flush=True)
                for c, msg in st.failures[-1:]:
                    print(f"  last failure: case {c}: {msg}", file=log, flush=True)
        flush()
    return st


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cases", type=int, default=100_000)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--start", type=int, default=0, help="first case number (to rerun a range)")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    st = run(a.cases, a.seed, log=sys.stderr, start=a.start)
    dt = time.perf_counter() - t0
    print(f"{st.cases} cases, {st.meshes} meshes checked, {st.rejected} MeshError rejections, {st.simple} simple "
          f"outputs ({st.realized} realized) in {st.peer_batches} peer batches, {len(st.failures)} failures, {dt:.1f} s")
    for case, msg in st.failures[:20]:
        print(f"case {case} (seed {a.seed}): {msg}")
    return 1 if st.failures else 0


if __name__ == "__main__":
    sys.exit(main())
